"""Signing and opening frames of a keyed bus, as firmware/edge/auth.c does (lcm_types/README.md, "An
authenticated bus"), with Debian's python3-cryptography for ChaCha20-Poly1305.

A frame is the message's LCM encoding followed by a 28-byte trailer: sender_id (4 bytes), counter
(8 bytes), both big-endian, and the tag: ChaCha20-Poly1305 with the 32-byte key, nonce = sender_id ||
counter, associated data = the channel's name, a zero byte, then the message; nothing is encrypted.

    import tvo.auth
    key = tvo.auth.read_key_file("robot.key")            # tools/keygen's file: 64 hex digits, mode 0600
    plant = tvo.auth.Link(key, tvo.auth.SENDER_PLANT)    # counters follow the wall clock, as tvo_sim's
    lc.publish("TVO_SAMPLE", plant.sign("TVO_SAMPLE", sample.encode()))
    message = plant.open("TVO_COMMAND", frame)           # AuthError (.reason) if forged, replayed, ...

The counters (wire v3): a plant's follow its wall clock in microseconds; a node's are (boot_id << 40) | n
(Link.count_from_boot). A receiver takes a sender it has not heard at any counter, then only higher ones:
no window, no clock; a recording from before a node's restart is kept out by the boot id a START names.
The constants (KEY_BYTES, SENDER_PLANT, BOOT_COUNTER_BITS, ...) are auth.h's, read at build time.
"""
import os
import stat
import struct
import time

from ._auth_h import (BOOT_COUNTER_BITS, KEY_BYTES, MAX_CHANNEL_BYTES, MAX_SENDERS, SENDER_FLEET_NODE,
                      SENDER_FLEET_ROBOT, SENDER_NODE, SENDER_PLANT, TAG_BYTES)

HEAD_BYTES = 4 + 8                      # sender_id, counter: the nonce
TRAILER_BYTES = HEAD_BYTES + TAG_BYTES  # auth.h's TVO_AUTH_TRAILER_BYTES
_HEAD = struct.Struct(">IQ")
_COUNTER_END = (1 << 64) - 1            # a counter of 2^64 - 1 is never signed: the sender is spent
MAX_BOOT_ID = (1 << (63 - BOOT_COUNTER_BITS)) - 1   # auth.h's TVO_AUTH_MAX_BOOT_ID: counters stay below 2^63

__all__ = ["AuthError", "Link", "read_key_file", "sign", "tag", "wall_clock_counter", "KEY_BYTES", "TAG_BYTES",
           "TRAILER_BYTES", "SENDER_NODE", "SENDER_PLANT", "SENDER_FLEET_NODE", "SENDER_FLEET_ROBOT",
           "BOOT_COUNTER_BITS", "MAX_BOOT_ID", "MAX_SENDERS", "MAX_CHANNEL_BYTES"]


class AuthError(ValueError):
    """A frame refused or a call misused; .reason is one of auth.c's outcomes: "argument", "truncated",
    "tag", "replay", "senders full", "counter spent" (a refused frame changed nothing)."""

    def __init__(self, reason, text):
        self.reason = reason
        super().__init__(text)


def _aead(key):
    try:
        from cryptography.hazmat.primitives.ciphers.aead import ChaCha20Poly1305
    except ImportError:
        raise ImportError("tvo.auth needs Python's cryptography (Debian python3-cryptography; "
                          "tools/setup python installs it)") from None
    return ChaCha20Poly1305(_key_bytes(key))


def _key_bytes(key):
    key = bytes(key)
    if len(key) != KEY_BYTES:
        raise AuthError("argument", f"a key is {KEY_BYTES} bytes, got {len(key)}")
    return key


def _channel_bytes(channel):
    name = channel.encode() if isinstance(channel, str) else bytes(channel)
    if not 1 <= len(name) <= MAX_CHANNEL_BYTES or b"\0" in name:
        raise AuthError("argument", f"a channel name is 1 .. {MAX_CHANNEL_BYTES} bytes without NUL, got {channel!r}")
    return name + b"\0"


def _uint(value, bits, what):
    if not isinstance(value, int) or not 0 <= value < (1 << bits):
        raise AuthError("argument", f"{what} must be an integer in 0 .. 2^{bits} - 1, got {value!r}")
    return value


def tag(key, channel, message, sender_id, counter):
    """The 16-byte tag of message on channel, signed as (sender_id, counter)."""
    head = _HEAD.pack(_uint(sender_id, 32, "sender_id"), _uint(counter, 64, "counter"))
    return _aead(key).encrypt(head, b"", _channel_bytes(channel) + bytes(message))


def sign(key, channel, message, sender_id, counter):
    """message followed by its trailer (stateless: the caller never repeats a (sender_id, counter))."""
    tag16 = tag(key, channel, message, sender_id, counter)   # checks the arguments first
    return bytes(message) + _HEAD.pack(sender_id, counter) + tag16


def wall_clock_counter():
    """A host sender's counter floor: microseconds since the Unix epoch, at least 1 (auth_key_file.c)."""
    return max(1, time.time_ns() // 1000)


def read_key_file(path):
    """The 32-byte key of a key file (tools/keygen): a regular file only its owner may access, holding
    64 hexadecimal digits and at most a newline. OSError / ValueError naming the file and what is wrong."""
    fd = os.open(path, os.O_RDONLY | os.O_NOCTTY)
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"key file '{path}': not a regular file")
        if st.st_mode & (stat.S_IRWXG | stat.S_IRWXO):
            raise ValueError(f"key file '{path}': group or others may access it: a key must be the owner's "
                             "alone (chmod 600)")
        text = os.read(fd, 2 * KEY_BYTES + 3)
    finally:
        os.close(fd)
    if text.endswith(b"\n"):
        text = text[:-1]
    if len(text) != 2 * KEY_BYTES:
        raise ValueError(f"key file '{path}': expected {2 * KEY_BYTES} hexadecimal digits ({KEY_BYTES} bytes) "
                         "and at most a newline")
    try:
        return bytes.fromhex(text.decode("ascii"))
    except (UnicodeDecodeError, ValueError):
        raise ValueError(f"key file '{path}': a character that is not a hexadecimal digit") from None


class Link:
    """One keyed end, as tvo_auth_t: signs as sender_id with increasing counters, and opens frames,
    remembering each sender's last counter (at most max_senders of them, for as long as it runs).

    start: the first counter (>= 1); by default the wall clock, and every counter signed is then at
    least its reading (tvo_auth_follow_clock: a plant). A node's end calls count_from_boot(boot_id)."""

    def __init__(self, key, sender_id, start=None, max_senders=MAX_SENDERS):
        self._aead = _aead(key)
        self.sender_id = _uint(sender_id, 32, "sender_id")
        self._follow_clock = start is None
        start = wall_clock_counter() if start is None else _uint(start, 64, "start")
        if start < 1:
            raise AuthError("argument", "the first counter must be >= 1")
        self.next_counter = start
        self.counter_end = _COUNTER_END      # the first counter this end may not sign
        self.max_senders = max_senders
        self.senders = {}   # sender_id -> the last counter accepted

    def count_from_boot(self, boot_id):
        """Sign from (boot_id << BOOT_COUNTER_BITS) | 1 on, never past that boot's range (tvo_auth_count_from_boot):
        a node's counters, above every one of its earlier boots', with no clock."""
        if not isinstance(boot_id, int) or not 1 <= boot_id <= MAX_BOOT_ID:
            raise AuthError("argument", f"a boot id is an integer in 1 .. {MAX_BOOT_ID}, got {boot_id!r}")
        self.next_counter = (boot_id << BOOT_COUNTER_BITS) | 1
        self.counter_end = (boot_id + 1) << BOOT_COUNTER_BITS
        self._follow_clock = False

    def sign(self, channel, message):
        """The frame to publish: message and its trailer; consumes one counter."""
        name = _channel_bytes(channel)
        if self._follow_clock:
            self.next_counter = max(self.next_counter, wall_clock_counter())
        if self.next_counter >= self.counter_end:
            raise AuthError("counter spent", f"sender {self.sender_id}: counter {self.next_counter} is past its range")
        head = _HEAD.pack(self.sender_id, self.next_counter)
        frame = bytes(message) + head + self._aead.encrypt(head, b"", name + bytes(message))
        self.next_counter += 1
        return frame

    def open(self, channel, frame):
        """The message of a frame whose tag verifies and whose counter is above its sender's last (a
        sender not heard yet: any counter); else AuthError, and nothing is remembered. The order is
        auth.c's, cheapest first: truncated, a known sender's used counter (no tag computed), the tag,
        room for a new sender."""
        from cryptography.exceptions import InvalidTag
        name = _channel_bytes(channel)
        frame = bytes(frame)
        if len(frame) < TRAILER_BYTES:
            raise AuthError("truncated", f"{len(frame)} bytes: shorter than an authentication trailer "
                                         f"({TRAILER_BYTES} bytes)")
        message, head, received = frame[:-TRAILER_BYTES], frame[-TRAILER_BYTES:-TAG_BYTES], frame[-TAG_BYTES:]
        sender_id, counter = _HEAD.unpack(head)
        last = self.senders.get(sender_id)
        if last is not None and counter <= last:
            raise AuthError("replay", f"sender {sender_id}: counter {counter} not above its last, {last} (a replay)")
        try:
            # decrypt() checks the tag in constant time (a forger learns nothing from the timing)
            self._aead.decrypt(head, received, name + message)
        except InvalidTag:
            raise AuthError("tag", "tag does not verify (forged, altered, another key or another channel)") from None
        if last is None and len(self.senders) >= self.max_senders:
            raise AuthError("senders full", f"sender {sender_id}: already {self.max_senders} senders to remember")
        self.senders[sender_id] = counter
        return message
