#!/usr/bin/python3
"""LCM 1.3's Python module (lcm-python/ of Debian's lcm source package) made to build and run on
Python 3.10 and later, as LCM's later releases changed it; written as copies into OUT_DIR.

Each change replaces an exact text a known number of times, so a source that differs stops the build
instead of being half changed:
  - PY_SSIZE_T_CLEAN before Python.h: since 3.10, "#" formats (s#, y#) need it, and their lengths are
    then Py_ssize_t: the variables PyArg_ParseTuple writes become Py_ssize_t, the lengths
    Py_BuildValue reads are cast to it;
  - Py_TYPE(&t) = &PyType_Type becomes Py_SET_TYPE (Py_TYPE is no longer an lvalue since 3.10);
  - PyEval_CallObject (deprecated in 3.9, removed in 3.13) becomes PyObject_CallObject, the same call.

Usage: lcm_python_patch.py LCM_PYTHON_DIR OUT_DIR   (writes OUT_DIR/{module,pyeventlog,pylcm,pylcm_subscription}.c)
"""
import os
import sys

CLEAN = ("#include <Python.h>", "#define PY_SSIZE_T_CLEAN\n#include <Python.h>")
CHANGES = {
    "module.c": [CLEAN,
                 ("Py_TYPE(&pylcmeventlog_type) = &PyType_Type;", "Py_SET_TYPE(&pylcmeventlog_type, &PyType_Type);"),
                 ("Py_TYPE(&pylcm_type) = &PyType_Type;", "Py_SET_TYPE(&pylcm_type, &PyType_Type);"),
                 ("Py_TYPE(&pylcm_subscription_type) = &PyType_Type;",
                  "Py_SET_TYPE(&pylcm_subscription_type, &PyType_Type);")],
    "pyeventlog.c": [CLEAN,
                     ("next_event->channel, next_event->channellen,",
                      "next_event->channel, (Py_ssize_t)next_event->channellen,", 2),
                     ("next_event->data, next_event->datalen);", "next_event->data, (Py_ssize_t)next_event->datalen);", 2),
                     ("    int channellen = 0;", "    Py_ssize_t channellen = 0;"),
                     ("    int datalen = 0;", "    Py_ssize_t datalen = 0;")],
    "pylcm.c": [CLEAN,
                ("rbuf->data, rbuf->data_size);", "rbuf->data, (Py_ssize_t)rbuf->data_size);", 2),
                ("PyEval_CallObject (subs_obj->handler, arglist)", "PyObject_CallObject (subs_obj->handler, arglist)"),
                ("    int chan_len = 0;", "    Py_ssize_t chan_len = 0;"),
                ("    int datalen = 0;", "    Py_ssize_t datalen = 0;")],
    "pylcm_subscription.c": [],   # includes Python.h through pylcm_subscription.h: the define goes first
}


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    source, out = argv[1:]
    os.makedirs(out, exist_ok=True)
    for name, changes in CHANGES.items():
        path = os.path.join(source, name)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        if name == "pylcm_subscription.c":
            text = "#define PY_SSIZE_T_CLEAN\n" + text
        for change in changes:
            old, new, count = change if len(change) == 3 else (*change, 1)
            found = text.count(old)
            if found != count:
                sys.exit(f"lcm_python_patch.py: {path}: '{old}' found {found} times, expected {count} "
                         "(another LCM release? its module may need other changes)")
            text = text.replace(old, new)
        if "PY_SSIZE_T_CLEAN" not in text:
            sys.exit(f"lcm_python_patch.py: {path}: no #include <Python.h> to put PY_SSIZE_T_CLEAN before")
        with open(os.path.join(out, name), "w", encoding="utf-8") as f:
            f.write(text)


if __name__ == "__main__":
    main(sys.argv)
