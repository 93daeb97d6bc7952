"""Signing and opening frames of a keyed bus, as firmware/edge/auth.c does (lcm_types/README.md, "An
authenticated bus"), with Debian's python3-cryptography for ChaCha20-Poly1305.

A frame is the message's LCM encoding followed by a 28-byte trailer: sender_id (4 bytes), counter
(8 bytes), both big-endian, and the tag: ChaCha20-Poly1305 with the 32-byte key, nonce = sender_id ||
counter, associated data = the channel's name, a zero byte, then the message; nothing is encrypted.

    import tvo.auth
    key = tvo.auth.read_key_file("robot.key")            # tools/keygen's file: 64 hex digits, mode 0600
    plant = tvo.auth.Link(key, tvo.auth.SENDER_PLANT)    # counters follow the wall clock, as tvo_sim's
    lc.publish("TVO_MEASUREMENT", plant.sign("TVO_MEASUREMENT", measurement.encode()))
    message = plant.open("TVO_COMMAND", frame)           # AuthError (.reason) if forged, replayed, ...

The constants (KEY_BYTES, SENDER_PLANT, NEW_SENDER_WINDOW_US, ...) are auth.h's, read at build time.
"""
import os
import stat
import struct
import time

from ._auth_h import (KEY_BYTES, MAX_CHANNEL_BYTES, MAX_SENDERS, NEW_SENDER_WINDOW_US, SENDER_FLEET_NODE,
                      SENDER_FLEET_ROBOT, SENDER_NODE, SENDER_PLANT, TAG_BYTES)

HEAD_BYTES = 4 + 8                      # sender_id, counter: the nonce
TRAILER_BYTES = HEAD_BYTES + TAG_BYTES  # auth.h's TVO_AUTH_TRAILER_BYTES
_HEAD = struct.Struct(">IQ")
_COUNTER_END = (1 << 64) - 1            # a counter of 2^64 - 1 is never signed: the sender is spent

__all__ = ["AuthError", "Link", "read_key_file", "sign", "tag", "wall_clock_counter", "KEY_BYTES", "TAG_BYTES",
           "TRAILER_BYTES", "SENDER_NODE", "SENDER_PLANT", "SENDER_FLEET_NODE", "SENDER_FLEET_ROBOT",
           "NEW_SENDER_WINDOW_US", "MAX_SENDERS", "MAX_CHANNEL_BYTES"]


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
    remembering each sender's last counter (at most max_senders of them).

    start: the first counter, and the floor a sender not heard yet must start above is start -
    window_us (tvo_auth_start_at); by default the wall clock, and every counter signed is at least its
    reading (tvo_auth_follow_clock, what tvo_sim and the node do on a host)."""

    def __init__(self, key, sender_id, start=None, window_us=NEW_SENDER_WINDOW_US, max_senders=MAX_SENDERS):
        self._aead = _aead(key)
        self.sender_id = _uint(sender_id, 32, "sender_id")
        self._follow_clock = start is None
        start = wall_clock_counter() if start is None else _uint(start, 64, "start")
        if start < 1:
            raise AuthError("argument", "the first counter must be >= 1")
        self.next_counter = start
        self.new_sender_floor = max(0, start - _uint(window_us, 64, "window_us"))
        self.max_senders = max_senders
        self.senders = {}   # sender_id -> the last counter accepted

    def sign(self, channel, message):
        """The frame to publish: message and its trailer; consumes one counter."""
        name = _channel_bytes(channel)
        if self._follow_clock:
            self.next_counter = max(self.next_counter, wall_clock_counter())
        if self.next_counter >= _COUNTER_END:
            raise AuthError("counter spent", f"sender {self.sender_id}: counter exhausted")
        head = _HEAD.pack(self.sender_id, self.next_counter)
        frame = bytes(message) + head + self._aead.encrypt(head, b"", name + bytes(message))
        self.next_counter += 1
        return frame

    def open(self, channel, frame):
        """The message of a frame whose tag verifies and whose counter is above its sender's last;
        else AuthError, and nothing is remembered."""
        from cryptography.exceptions import InvalidTag
        name = _channel_bytes(channel)
        frame = bytes(frame)
        if len(frame) < TRAILER_BYTES:
            raise AuthError("truncated", f"{len(frame)} bytes: shorter than an authentication trailer "
                                         f"({TRAILER_BYTES} bytes)")
        message, head, received = frame[:-TRAILER_BYTES], frame[-TRAILER_BYTES:-TAG_BYTES], frame[-TAG_BYTES:]
        try:
            # decrypt() checks the tag in constant time (a forger learns nothing from the timing)
            self._aead.decrypt(head, received, name + message)
        except InvalidTag:
            raise AuthError("tag", "tag does not verify (forged, altered, another key or another channel)") from None
        sender_id, counter = _HEAD.unpack(head)
        last = self.senders.get(sender_id)
        if last is not None and counter <= last:
            raise AuthError("replay", f"sender {sender_id}: counter {counter} not above its last, {last} (a replay)")
        if last is None:
            if counter <= self.new_sender_floor:
                raise AuthError("replay", f"sender {sender_id} not heard yet: counter {counter} not above "
                                          f"{self.new_sender_floor} (older than this end's start - window: a replay)")
            if len(self.senders) >= self.max_senders:
                raise AuthError("senders full", f"sender {sender_id}: already {self.max_senders} senders to remember")
        self.senders[sender_id] = counter
        return message
