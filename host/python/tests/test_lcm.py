#!/usr/bin/python3
"""LCM from Python: LCM's own module (built from Debian's lcm source package) and the message types
lcm-gen -p generated from lcm_types/*.lcm publish and receive over memq:// and over UDP multicast on
loopback; every generated type round-trips; an LCM log written from Python reads back; a frame
signed with tvo.auth travels and opens; examples/plant.py applies commands by rule 4.

Usage: test_lcm.py UDPM_URL   (PYTHONPATH: <build>/host/python)
"""
import importlib
import importlib.util
import os
import re
import sys
import tempfile
import unittest

try:
    import lcm
except ImportError as e:
    print(f"skipped: LCM's Python module is not built ({e}): tools/setup python fetches Debian's lcm source")
    sys.exit(77)

import tvo_lcm

URL = None


def generated_types():
    """Every type lcm-gen wrote into tvo_lcm (its __init__ imports each)."""
    names = sorted(n for n in dir(tvo_lcm) if n.endswith("_t") and isinstance(getattr(tvo_lcm, n), type))
    return [getattr(tvo_lcm, n) for n in names]


def sample_command():
    """Robot 1's command of a v3 session: one robot per message, a nested header."""
    m = tvo_lcm.unicycle_command_t()
    m.header.utime, m.header.session_id, m.header.measurement_sequence, m.header.robot = 1_000_000, 77, 12, 1
    m.speed_mps, m.turn_rate_radps = 0.5, -0.25
    return m


class Bus:
    """One LCM instance and what it received, by channel."""

    def __init__(self, url):
        self.lc = lcm.LCM(url)
        self.got = []

    def listen(self, channel):
        self.lc.subscribe(channel, lambda ch, data: self.got.append((ch, data)))

    def receive(self, count, timeout_ms=2000):
        for _ in range(100):
            if len(self.got) >= count:
                break
            self.lc.handle_timeout(timeout_ms // 100)
        return self.got


class LcmTest(unittest.TestCase):
    def test_every_struct_of_lcm_types_is_generated(self):
        lcm_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "lcm_types")
        structs = []
        for name in os.listdir(lcm_dir):
            if name.endswith(".lcm"):
                with open(os.path.join(lcm_dir, name), encoding="utf-8") as f:
                    text = re.sub(r"//[^\n]*|/\*.*?\*/", "", f.read(), flags=re.S)
                structs += re.findall(r"\bstruct\s+(\w+)", text)
        self.assertGreater(len(structs), 0)
        self.assertEqual([t.__name__ for t in generated_types()], sorted(structs))

    def check_bus(self, url):
        bus = Bus(url)
        bus.listen("TVO_PY_.*")
        types = generated_types()
        for t in types:
            bus.lc.publish(f"TVO_PY_{t.__name__}", t().encode())
        command = sample_command()
        bus.lc.publish("TVO_PY_COMMAND", command.encode())
        got = dict(bus.receive(len(types) + 1))
        self.assertEqual(len(got), len(types) + 1, f"received {sorted(got)} on {url}")
        for t in types:
            self.assertEqual(t.decode(got[f"TVO_PY_{t.__name__}"]).encode(), t().encode())
        back = tvo_lcm.unicycle_command_t.decode(got["TVO_PY_COMMAND"])
        self.assertEqual((back.header.session_id, back.header.measurement_sequence, back.header.robot), (77, 12, 1))
        self.assertEqual((back.speed_mps, back.turn_rate_radps), (0.5, -0.25))

    def test_memq(self):
        self.check_bus("memq://")

    def test_udpm_on_loopback(self):
        try:
            self.check_bus(URL)
        except (IOError, AssertionError) as e:
            raise AssertionError(f"{e}: if no multicast arrives on loopback, as root: ip link set lo multicast on; "
                                 "ip route add 224.0.0.0/4 dev lo") from e

    def test_event_log(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "py.lcmlog")
            log = lcm.EventLog(path, "w")
            log.write_event(123, "TVO_COMMAND", sample_command().encode())
            log.close()
            events = list(lcm.EventLog(path, "r"))
        self.assertEqual([(e.timestamp, e.channel) for e in events], [(123, "TVO_COMMAND")])
        self.assertEqual(tvo_lcm.unicycle_command_t.decode(events[0].data).header.session_id, 77)

    def test_a_signed_frame_travels_and_opens(self):
        auth = importlib.import_module("tvo.auth")
        key = bytes(range(32))
        plant, node = auth.Link(key, auth.SENDER_PLANT), auth.Link(key, auth.SENDER_NODE, start=1)
        node.count_from_boot(17)                                            # a node's counters: its boot's
        bus = Bus("memq://")
        bus.listen("TVO_COMMAND")
        bus.lc.publish("TVO_COMMAND", node.sign("TVO_COMMAND", sample_command().encode()))
        (channel, frame), = bus.receive(1)
        self.assertEqual(int.from_bytes(frame[-24:-16], "big"), (17 << 40) | 1)
        self.assertEqual(tvo_lcm.unicycle_command_t.decode(plant.open(channel, frame)).header.session_id, 77)
        # LCM's decoder reads the message and ignores the trailer
        self.assertEqual(tvo_lcm.unicycle_command_t.decode(frame).header.session_id, 77)

    def test_readme_block(self):
        """host/python/README.md's "LCM and signed frames" block runs as written (its assert checks it)."""
        readme = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "README.md")
        with open(readme, encoding="utf-8") as f:
            block = re.search(r"<!-- snippet:python-lcm begin -->\n```python\n(.*?)```\n<!-- snippet:python-lcm end -->",
                              f.read(), re.S)
        self.assertIsNotNone(block)
        scope = {}
        exec(block.group(1), scope)   # pylint: disable=exec-used
        self.assertEqual(scope["heard"][0].header.sequence, 1)


class ExamplePlantRule4Test(unittest.TestCase):
    """examples/plant.py's on_command (lcm_types/README.md, rule 4), fed encoded commands directly."""

    def plant(self):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "plant.py")
        spec = importlib.util.spec_from_file_location("example_plant", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        plant = module.Plant.__new__(module.Plant)  # no bus: only what on_command reads and writes
        plant.session_id, plant.sent, plant.in_force, plant.answered, plant.next = 77, 12, 11, False, None
        return plant

    @staticmethod
    def command(sequence, status=0, flags=0):
        m = sample_command()
        m.header.robot, m.header.measurement_sequence, m.header.status, m.header.flags = 0, sequence, status, flags
        return m

    def test_a_safe_stop_of_a_strays_sequence_does_not_hide_the_next_answer(self):
        plant = self.plant()
        stop = tvo_lcm.command_header_t.FLAG_SAFE_STOP
        plant.on_command(self.command(10**9, tvo_lcm.command_header_t.STATUS_ERR_WATCHDOG, stop).encode())
        self.assertEqual(plant.next.speed_mps, 0.5)   # applied on arrival (this test's stop keeps its inputs)
        self.assertEqual(plant.next.header.utime, 0)
        self.assertEqual(plant.in_force, 11)          # a sequence it never sent moves nothing
        plant.on_command(self.command(12).encode())  # the answer to its newest sample
        self.assertEqual(plant.next.header.measurement_sequence, 12)
        self.assertEqual(plant.in_force, 12)
        plant.next = None
        plant.on_command(self.command(12).encode())  # a repeat: not newer than the one in force
        self.assertIsNone(plant.next)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    URL = sys.argv.pop(1)
    unittest.main(verbosity=2)
