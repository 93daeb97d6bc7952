"""The two compiled cores (float32 and float64), their status codes as Python enums and exceptions."""
import enum
import importlib

import numpy as np

PRECISIONS = ("float32", "float64")
_MODULES = {"float32": "tvo._core_f32", "float64": "tvo._core_f64"}
_cores = {}


class Core:
    """One precision's extension: its ffi, lib and the numpy dtype of tvo_real_t."""

    def __init__(self, precision):
        if precision not in _MODULES:
            raise ValueError(f"precision must be one of {PRECISIONS}, got {precision!r}")
        module = importlib.import_module(_MODULES[precision])
        self.precision = precision
        self.ffi = module.ffi
        self.lib = module.lib
        size = self.ffi.sizeof("tvo_real_t")
        self.dtype = np.dtype(np.float32 if size == 4 else np.float64)
        if self.dtype != np.dtype(precision):
            raise ImportError(f"{_MODULES[precision]} was built with a {size}-byte tvo_real_t, not {precision}")

    def real_array(self, values, shape):
        """A new tvo_real_t[] of len prod(shape), filled from values (rounded to tvo_real_t as C does)."""
        flat = np.asarray(values, dtype=np.float64).reshape(-1)
        out = self.ffi.new("tvo_real_t[]", int(np.prod(shape)))
        for i, v in enumerate(flat):
            out[i] = float(v)
        return out


def core(precision="float32"):
    if precision not in _cores:
        _cores[precision] = Core(precision)
    return _cores[precision]


def _constants(*prefixes, strip=""):
    """The lib's integer constants whose names start with one of prefixes, by value (build_ffi.py
    declares every enumerator and flag of tvo/status.h; their values come from the compiler)."""
    lib = core("float32").lib
    names = [n for n in dir(lib) if n.startswith(prefixes) and isinstance(getattr(lib, n), int)]
    return {n[len(strip):]: getattr(lib, n) for n in sorted(names, key=lambda n: getattr(lib, n))}


def _named_enum(name, doc, prefix, text_fn, strip=""):
    """An IntEnum of the lib's constants named prefix* (but prefix + COUNT), str() the core's text."""
    values = {n: v for n, v in _constants(prefix, strip=strip).items() if n != (prefix + "COUNT")[len(strip):]}

    def message(self):
        return core().ffi.string(getattr(core().lib, text_fn)(int(self))).decode()

    cls = enum.IntEnum(name, values, module=__name__)
    cls.__doc__ = doc
    cls.message = property(message)
    cls.__str__ = lambda self: f"{self.name}: {self.message}"
    return cls


# tvo_status_t (tvo/status.h): a call's answer; anything but TVO_OK raises TvoError (the call changed nothing).
_StatusBase = enum.IntEnum("_StatusBase", {n: v for n, v in _constants("TVO_OK", "TVO_ERR_").items()})


class Status(enum.IntEnum):
    """tvo_status_t: 0 is TVO_OK; the others say a call failed and changed nothing. str() is the core's
    own text (tvo_status_str). Not the wire's numbers (command_t.status: the edge maps them)."""

    _ignore_ = ["member"]
    for member in _StatusBase:
        locals()[member.name] = int(member)

    @property
    def message(self):
        return core().ffi.string(core().lib.tvo_status_str(int(self))).decode()

    def __str__(self):
        return f"{self.name}: {self.message}"


# What a period did (tvo_outcome_t) and why it held or stopped (tvo_reason_t): a Command carries both.
Outcome = _named_enum("Outcome", "tvo_outcome_t: APPLIED, HELD or STOPPED (tvo_outcome_str).", "TVO_OUTCOME_",
                      "tvo_outcome_str", strip="TVO_OUTCOME_")
Reason = _named_enum("Reason", "tvo_reason_t: why a period held or stopped, NONE when applied (tvo_reason_str).",
                     "TVO_REASON_", "tvo_reason_str", strip="TVO_REASON_")


def _param_enum(name, doc, prefix, text_fn):
    """An IntEnum of a configuration's parameter names (prefix*, but prefix + COUNT); .field and str()
    are the field's name in the config (text_fn: tvo_param_str or tvo_chain_param_str)."""
    cls = enum.IntEnum(name, {n: v for n, v in _constants(prefix).items() if n != prefix + "COUNT"}, module=__name__)
    cls.__doc__ = doc
    cls.field = property(lambda self: core().ffi.string(getattr(core().lib, text_fn)(int(self))).decode())
    cls.__str__ = lambda self: self.field
    return cls


Param = _param_enum("Param", "tvo_param_t: which field of tvo_controller_config_t an init refused (tvo_param_str).",
                    "TVO_PARAM_", "tvo_param_str")
ChainParam = _param_enum("ChainParam", "tvo_chain_param_t: which field of tvo_chain_config_t an init refused "
                         "(tvo_chain_param_str).", "TVO_CHAIN_PARAM_", "tvo_chain_param_str")


# TVO_FLAG_*: what shaped an applied command (tvo_command_t.flags), e.g. Flag.PREDICTED in Flag(cmd.flags).
Flag = enum.IntFlag("Flag", _constants("TVO_FLAG_", strip="TVO_FLAG_"))

# The parts of a problem tvo_problem_init names on failure (tvo_problem_culprit_t.part, tvo/problem.h).
PROBLEM_PARTS = ("robots/targets", "barrier", "distance bounds", "half-spaces", "obstacles", "offsets")


class TvoError(Exception):
    """A status other than TVO_OK from the core (the call changed nothing): .status (Status), .param
    (Param, or ChainParam, for TVO_ERR_PARAM from an init), .part (the problem's part, from
    tvo_problem_init), .culprit (the entry the core refused, e.g. "obstacles[1]", when found) and
    .detail (what is wrong with it); the message is the core's text, then culprit and detail."""

    def __init__(self, status, where="", param=None, part=None, param_enum=None, culprit=None, detail=None):
        self.status = Status(status)
        self.param = (param_enum or Param)(param) if param is not None and int(param) != 0 else None
        self.part = part
        self.culprit = culprit
        self.detail = detail
        text = f"{where}: " if where else ""
        text += f"{self.status.name} ({self.status.message})"
        if self.param is not None:
            text += f", parameter {self.param.field}"
        if part is not None:
            text += f", part of the problem: {part}"
        if culprit is not None:
            text += f": {culprit}"
        if detail is not None:
            text += f": {detail}"
        super().__init__(text)


def check(status, where="", **kw):
    if int(status) != 0:
        raise TvoError(status, where, **kw)
