#!/usr/bin/python3
"""tvo.auth signs frames as firmware/edge/auth.c does and opens them by its rules.

Signing: the test vectors of tests/edge/test_auth.c (key bytes(range(32))): its three independent ones
(each tag must also appear in that file) and its table of one vector per wire message, read from the
file itself, so the two tests check the same vectors. Opening, by the v3 rules: a genuine stream opens;
a forged, altered, truncated, re-channelled or replayed frame is refused with auth.c's reason and
changes nothing; a known sender's used counter is a replay before any tag is computed; a sender not
heard yet is taken at any counter (no window); the sender table fills. Counters: a node's from its
boot ((boot << 40) | n, spent at its boot's end), a plant's following its clock and never going back.
Key files as auth_key_file.c reads them.

Usage: test_auth.py TEST_AUTH_C   (PYTHONPATH: <build>/host/python)
"""
import os
import re
import stat
import sys
import tempfile
import unittest

try:
    import cryptography  # noqa: F401  (Debian python3-cryptography)
except ImportError:
    print("skipped: Python's cryptography (Debian python3-cryptography; tools/setup python) is not installed")
    sys.exit(77)

from tvo import auth

KEY = bytes(range(32))
# tests/edge/test_auth.c, test_tags_match_an_independent_implementation: (channel, message, sender, counter, tag)
VECTORS = [
    ("TVO_MEASUREMENT", b"tvo-flat worked example", 7, 1, "f587554e608400e45f818031d640c10f"),
    ("TVO_COMMAND", b"", 0x01020304, 0x0102030405060708, "5637ac1861b8a7ad2b93ee4747f8c4c4"),
    ("TVO_MEASUREMENT", bytes((i * 7 + 3) & 255 for i in range(300)), 0xFFFFFFFE, 123456789012345,
     "df84f13d080971720a813ef64c3c8376"),
]
TEST_AUTH_C = None


def message_vectors(c_text):
    """test_auth.c's message_vectors table: (type, channel, sender, counter, tag hex, message bytes)."""
    table = c_text[c_text.index("message_vectors[] = {"):]
    table = table[:table.index("};")]
    rows = re.findall(r'\{"(\w+)", "(\w+)", (\d+)u, UINT64_C\((\d+)\), "([0-9a-f]{32})",((?:\s*"[0-9a-f]*")+)\s*\}',
                      table)
    return [(t, ch, int(sender), int(counter), tag_hex, bytes.fromhex("".join(re.findall(r'"([0-9a-f]*)"', hexes))))
            for t, ch, sender, counter, tag_hex, hexes in rows]


class SignTest(unittest.TestCase):
    def test_vectors_of_test_auth_c(self):
        with open(TEST_AUTH_C, encoding="utf-8") as f:
            c_text = f.read()
        for channel, message, sender, counter, tag_hex in VECTORS:
            self.assertIn(f'"{tag_hex}"', c_text)   # the C test checks this very vector
            frame = auth.sign(KEY, channel, message, sender, counter)
            self.assertEqual(len(frame), len(message) + auth.TRAILER_BYTES)
            self.assertEqual(frame[:len(message)], message)
            self.assertEqual(frame[len(message):len(message) + 12], sender.to_bytes(4, "big") + counter.to_bytes(8, "big"))
            self.assertEqual(frame[-16:].hex(), tag_hex)
            link = auth.Link(KEY, sender, start=counter)
            self.assertEqual(link.sign(channel, message), frame)
            self.assertEqual(link.next_counter, counter + 1)

    def test_message_vectors_of_test_auth_c(self):
        with open(TEST_AUTH_C, encoding="utf-8") as f:
            vectors = message_vectors(f.read())
        self.assertEqual(len(vectors), 8)   # every per-period, session-ack and announcement message of the wire
        for type_name, channel, sender, counter, tag_hex, message in vectors:
            with self.subTest(type_name):
                frame = auth.sign(KEY, channel, message, sender, counter)
                self.assertEqual(frame[-16:].hex(), tag_hex)
                self.assertEqual(auth.Link(KEY, 99, start=1).open(channel, frame), message)

    def test_constants_are_auth_h(self):
        self.assertEqual((auth.KEY_BYTES, auth.TAG_BYTES, auth.TRAILER_BYTES), (32, 16, 28))
        self.assertEqual((auth.SENDER_NODE, auth.SENDER_PLANT), (1, 2))
        self.assertEqual((auth.SENDER_FLEET_NODE, auth.SENDER_FLEET_ROBOT), (0x100, 0x200))
        self.assertEqual((auth.BOOT_COUNTER_BITS, auth.MAX_BOOT_ID, auth.MAX_SENDERS), (40, 8388607, 40))
        self.assertFalse(hasattr(auth, "NEW_SENDER_WINDOW_US"))   # v3: no window

    def test_arguments(self):
        for call in (lambda: auth.sign(KEY[:31], "C", b"", 1, 1), lambda: auth.sign(KEY, "", b"", 1, 1),
                     lambda: auth.sign(KEY, "C" * 65, b"", 1, 1), lambda: auth.sign(KEY, "C", b"", 1 << 32, 1),
                     lambda: auth.Link(KEY, 1, start=0)):
            with self.assertRaises(auth.AuthError) as caught:
                call()
            self.assertEqual(caught.exception.reason, "argument")

    def test_counters_follow_the_wall_clock(self):
        link = auth.Link(KEY, auth.SENDER_PLANT)
        before = auth.wall_clock_counter()
        frame = link.sign("TVO_SAMPLE", b"x")
        counter = int.from_bytes(frame[-24:-16], "big")
        self.assertGreaterEqual(counter, before)
        self.assertGreater(int.from_bytes(link.sign("TVO_SAMPLE", b"x")[-24:-16], "big"), counter)

    def test_a_plant_never_goes_back_with_its_clock(self):
        # test_auth.c's test_a_plant_follows_its_clock, with the clock faked
        clock = [1_700_000_000_000_000]
        real = auth.wall_clock_counter
        auth.wall_clock_counter = lambda: clock[0]
        try:
            link = auth.Link(KEY, auth.SENDER_PLANT)
            counters = []
            for step_us in (0, -5_000_000, 10_000_000):
                clock[0] += step_us
                counters.append(int.from_bytes(link.sign("TVO_SAMPLE", b"x")[-24:-16], "big"))
        finally:
            auth.wall_clock_counter = real
        self.assertEqual(counters, [1_700_000_000_000_000, 1_700_000_000_000_001, 1_700_000_005_000_000])

    def test_a_node_counts_from_its_boot(self):
        node, plant = auth.Link(KEY, auth.SENDER_NODE, start=1), auth.Link(KEY, auth.SENDER_PLANT, start=1)
        for bad in (0, -1, auth.MAX_BOOT_ID + 1, 1.5, None):
            with self.assertRaises(auth.AuthError) as caught:
                node.count_from_boot(bad)
            self.assertEqual(caught.exception.reason, "argument")
            self.assertEqual(node.next_counter, 1)
        node.count_from_boot(5)
        for n in (1, 2, 3):
            frame = node.sign("TVO_NODE", b"status")
            self.assertEqual(int.from_bytes(frame[-24:-16], "big"), (5 << 40) | n)
            self.assertEqual(plant.open("TVO_NODE", frame), b"status")
        restarted = auth.Link(KEY, auth.SENDER_NODE, start=1)   # the next boot: above every counter of the last
        restarted.count_from_boot(6)
        self.assertEqual(plant.open("TVO_NODE", restarted.sign("TVO_NODE", b"status")), b"status")
        node.next_counter = (6 << 40) - 1                      # boot 5's last counter signs; the next is spent
        node.sign("TVO_NODE", b"status")
        with self.assertRaises(auth.AuthError) as caught:
            node.sign("TVO_NODE", b"status")
        self.assertEqual(caught.exception.reason, "counter spent")
        self.assertEqual(node.next_counter, 6 << 40)
        node.count_from_boot(auth.MAX_BOOT_ID)
        self.assertEqual(node.counter_end, 1 << 63)


class OpenTest(unittest.TestCase):
    def setUp(self):
        self.sender = auth.Link(KEY, 42, start=1000)
        self.receiver = auth.Link(KEY, 1, start=1)

    def refused(self, reason, channel, frame):
        senders = dict(self.receiver.senders)
        with self.assertRaises(auth.AuthError) as caught:
            self.receiver.open(channel, frame)
        self.assertEqual(caught.exception.reason, reason)
        self.assertEqual(self.receiver.senders, senders)   # nothing of a refused frame is kept

    def test_a_genuine_stream_opens_and_a_replay_is_refused(self):
        first = self.sender.sign("TVO_SAMPLE", b"sample one")
        self.assertEqual(self.receiver.open("TVO_SAMPLE", first), b"sample one")
        second = self.sender.sign("TVO_SAMPLE", b"sample two")
        self.assertEqual(self.receiver.open("TVO_SAMPLE", second), b"sample two")
        self.refused("replay", "TVO_SAMPLE", first)
        self.refused("replay", "TVO_SAMPLE", second)
        self.assertEqual(self.receiver.senders, {42: 1001})

    def test_forged_altered_truncated_or_moved_frames_are_refused(self):
        frame = self.sender.sign("TVO_SAMPLE", b"sample")
        altered = bytearray(frame)
        altered[0] ^= 1
        self.refused("tag", "TVO_SAMPLE", bytes(altered))
        self.refused("tag", "TVO_COMMAND", frame)                        # moved to another channel
        self.refused("tag", "TVO_SAMPLE", auth.Link(bytes(32), 42, start=2000).sign("TVO_SAMPLE", b"sample"))
        self.refused("truncated", "TVO_SAMPLE", frame[-auth.TRAILER_BYTES + 1:])
        self.refused("tag", "TVO_SAMPLE", frame[1:])
        self.assertEqual(self.receiver.open("TVO_SAMPLE", frame), b"sample")   # the genuine one still opens

    def test_a_used_counter_is_refused_before_the_tag(self):
        frame = self.sender.sign("TVO_SAMPLE", b"genuine")
        self.receiver.open("TVO_SAMPLE", frame)
        forged = bytearray(frame)
        forged[-16:] = b"\xa5" * 16                                      # a garbage tag
        self.refused("replay", "TVO_SAMPLE", bytes(forged))
        forged[-auth.TRAILER_BYTES] ^= 1                                  # another sender, not heard yet
        self.refused("tag", "TVO_SAMPLE", bytes(forged))
        forged[-auth.TRAILER_BYTES] ^= 1
        forged[-auth.TRAILER_BYTES + 4] = 1                               # the known sender, a higher counter
        self.refused("tag", "TVO_SAMPLE", bytes(forged))

    def test_a_new_sender_is_taken_at_any_counter_and_the_table_fills(self):
        receiver = auth.Link(KEY, 1, start=10_000_000, max_senders=2)
        self.assertEqual(receiver.open("C", auth.sign(KEY, "C", b"old", 5, 1)), b"old")   # no window
        self.assertEqual(receiver.open("C", auth.sign(KEY, "C", b"new", 6, 9_000_001)), b"new")
        with self.assertRaises(auth.AuthError) as caught:
            receiver.open("C", auth.sign(KEY, "C", b"new", 7, 9_000_001))
        self.assertEqual(caught.exception.reason, "senders full")
        self.assertEqual(receiver.senders, {5: 1, 6: 9_000_001})


class KeyFileTest(unittest.TestCase):
    def write(self, folder, text, mode=0o600):
        path = os.path.join(folder, "robot.key")
        with open(path, "w", encoding="ascii") as f:
            f.write(text)
        os.chmod(path, mode)
        return path

    def test_key_files_as_auth_key_file_c(self):
        with tempfile.TemporaryDirectory() as folder:
            self.assertEqual(auth.read_key_file(self.write(folder, KEY.hex() + "\n")), KEY)
            self.assertEqual(auth.read_key_file(self.write(folder, KEY.hex().upper(), 0o400)), KEY)
            for text, mode, why in ((KEY.hex(), 0o640, "chmod 600"), (KEY.hex()[:-2], 0o600, "64 hexadecimal digits"),
                                    (KEY.hex() + "\n\n", 0o600, "64 hexadecimal digits"),
                                    ("g" + KEY.hex()[1:], 0o600, "not a hexadecimal digit")):
                with self.assertRaises(ValueError) as caught:
                    auth.read_key_file(self.write(folder, text, mode))
                self.assertIn(why, str(caught.exception))
                self.assertIn("robot.key", str(caught.exception))
            with self.assertRaises(ValueError):
                auth.read_key_file(folder)
            self.assertFalse(stat.S_ISREG(os.stat(folder).st_mode))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    TEST_AUTH_C = sys.argv.pop(1)
    unittest.main(verbosity=2)
