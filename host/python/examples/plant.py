#!/usr/bin/python3
"""plant.py: an example plant for tvo_firmware_node on a keyed bus, in Python, for a robot team to copy
(lcm_types/README.md, "Writing your own plant", rules 1-6; host/examples/plant_client.c is the same in C).
Its robot is an exact unicycle tracking the demo's ellipse (host/scenarios/demo.yaml, tvo_sim's defaults)
in lockstep (CLOCK_PLANT): the plant's clock drives time; it samples, waits for the answer, applies it.
Every frame is signed and opened with tvo.auth (the key file of tools/keygen).

    plant.py --key-file robot.key [--lcm-url URL] [--duration-s 20]
    prints "final_error_m=<metres> restarts=<n> dropped_frames=<n>"; exit 0 if the session ran to its end,
    1 if no node took it (or, after rule 5, took it again)

Needs PYTHONPATH=<build>/host/python (or `pip install ./host/python`): LCM's Python module, the generated
tvo_lcm types, tvo.auth and tvo.wire (the channel names).
"""
import argparse
import math
import os
import sys
import time

import lcm
from tvo import auth, defaults, wire
from tvo_lcm import (command_header_t, node_status_t, path_t, session_ack_t, session_t, unicycle_command_t,
                     unicycle_sample_t)

PERIOD_US = defaults.PERIOD_US  # h: period j's command applies at EPOCH_US + j h
DELAY_US = defaults.DELAY_US    # tau: the sample for period j is taken at EPOCH_US + j h - tau
EPOCH_US = 1_000_000            # plant time at which the target's t = 0
WATCHDOG_PERIODS = defaults.WATCHDOG_PERIODS  # no command for this long: the robot stops itself (rule 5)
ANSWER_WAIT_S = 0.5      # lockstep: how long to wait for a sample's answer before counting it unanswered


class Robot:
    """The unicycle: its pose and the command it holds (zero-order hold), integrated on exact arcs."""

    def __init__(self):
        self.x, self.y, self.heading, self.v, self.w = -1.0, -2.0, 0.0, 0.0, 0.0   # at rest, demo.yaml's start
        self.now_us = self.applied_us = EPOCH_US

    def hold_for(self, dt):
        if abs(self.w) < 1e-9:
            self.x += self.v * dt * math.cos(self.heading)
            self.y += self.v * dt * math.sin(self.heading)
        else:
            h1 = self.heading + self.w * dt
            self.x += self.v / self.w * (math.sin(h1) - math.sin(self.heading))
            self.y -= self.v / self.w * (math.cos(h1) - math.cos(self.heading))
        self.heading += self.w * dt

    def advance_to(self, t_us, due):
        """Moves to plant time t_us, applying the command due (rule 4) at its instant, never in the past.
        Returns the command still to come (None once applied)."""
        if due is not None and due.header.utime <= t_us:
            at = max(due.header.utime, self.now_us)
            self.hold_for((at - self.now_us) * 1e-6)
            self.now_us = self.applied_us = at
            self.v, self.w = due.speed_mps, due.turn_rate_radps
            due = None
        self.hold_for((t_us - self.now_us) * 1e-6)
        self.now_us = t_us
        if t_us - self.applied_us >= WATCHDOG_PERIODS * PERIOD_US:
            self.v = self.w = 0.0     # rule 5: in lockstep the node cannot act during a silence: stop yourself
        return due

    def stop(self):
        self.v = self.w = 0.0


class Plant:
    """The bus end: signs what it sends, opens what it hears, and keeps what the rules need."""

    def __init__(self, url, key):
        self.lc = lcm.LCM(url) if url else lcm.LCM()   # no URL: LCM's default (LCM_DEFAULT_URL)
        self.link = auth.Link(key, auth.SENDER_PLANT)    # counters follow the wall clock
        self.session_id = (time.time_ns() // 1000 + os.getpid()) & 0x7FFFFFFF   # fresh per run
        self.boot_id, self.max_robots = 0, 0    # rule 1: the node's current boot, its robot limit
        self.restart = False        # rule 5: it restarted, or dropped our session
        self.running_seen, self.node_utime = False, 0
        self.ack = None
        self.sent, self.in_force, self.answered, self.next = -1, -1, False, None
        self.dropped = 0            # frames that did not open (forged, replayed, another key)
        for channel, handler in ((wire.NODE, self.on_node), (wire.SESSION_ACK, self.on_ack),
                                 (wire.COMMAND, self.on_command)):
            self.lc.subscribe(channel, self.opened(handler))

    def opened(self, handler):
        def receive(channel, frame):
            try:
                message = self.link.open(channel, frame)
            except auth.AuthError:
                self.dropped += 1
                return
            handler(message)
        return receive

    def publish(self, channel, message):
        self.lc.publish(channel, self.link.sign(channel, message.encode()))

    def on_node(self, data):   # rules 1 and 5
        s = node_status_t.decode(data)
        if s.protocol_version != node_status_t.PROTOCOL_VERSION or s.own_robot != -1:
            return
        if self.boot_id and s.boot_id > self.boot_id:
            self.restart = True     # a new boot: our session is gone
        if s.boot_id == self.boot_id and s.state == s.STATE_RUNNING and s.session_id == self.session_id:
            self.running_seen, self.node_utime = True, s.utime
        elif s.boot_id == self.boot_id and s.state == s.STATE_IDLE and self.running_seen and s.utime > self.node_utime:
            self.restart = True     # it ran ours and now runs nothing
        if s.boot_id >= self.boot_id:
            self.boot_id, self.max_robots = s.boot_id, s.max_robots

    def on_ack(self, data):
        a = session_ack_t.decode(data)
        if a.session_id == self.session_id and a.boot_id == self.boot_id:
            self.ack = a

    def on_command(self, data):  # rule 4
        c = unicycle_command_t.decode(data)
        h = c.header
        if h.session_id != self.session_id or h.robot != 0:
            return      # another plant's
        self.answered |= h.measurement_sequence == self.sent
        safe_stop = bool(h.flags & command_header_t.FLAG_SAFE_STOP)
        newer_ours = self.in_force < h.measurement_sequence <= self.sent
        if (h.status == 0 and newer_ours) or safe_stop:
            if newer_ours:      # a safe stop of a stray's sequence must not hide ours
                self.in_force = h.measurement_sequence
            if safe_stop:
                h.utime = 0     # never put off stopping
            self.next = c

    def request(self, session, action, utime):
        """Rules 1, 2 and 6: the session message names the node's boot, repeated every 100 ms until acked.
        The ack (None if none came): its status 0 is done, else why not."""
        for _ in range(50):
            if self.boot_id:
                break
            self.lc.handle_timeout(100)
        if session.robot_count > self.max_robots:
            return None     # no node heard, or one that cannot drive this many robots
        session.action, session.utime = action, utime
        session.node_boot_id[0] = self.boot_id
        self.ack, self.restart, self.running_seen = None, False, False
        for _ in range(100):
            if not self.boot_id or (self.ack is not None and self.ack.action == action):
                break
            self.publish(wire.SESSION, session)
            deadline = time.monotonic() + 0.1
            while self.ack is None and time.monotonic() < deadline:
                self.lc.handle_timeout(10)
        return self.ack if self.ack is not None and self.ack.action == action else None


def why_not(plant, ack):
    """Why a START did not run, as plant_client.c says it."""
    if not plant.boot_id:
        return "no node announced itself"
    if ack is None:
        return "not acknowledged" if plant.max_robots else "the node drives fewer robots"
    return f"refused: status {ack.status}, parameter {ack.bad_param}, part {ack.bad_part}, index {ack.bad_index}"


def demo_session(session_id):
    """The demo's session (tvo_sim's defaults; host/scenarios/demo.yaml's robot): rule 2's fields."""
    s = session_t()
    s.protocol_version, s.session_id = node_status_t.PROTOCOL_VERSION, session_id
    s.clock_source, s.epoch_utime, s.period_us, s.delay_us = s.CLOCK_PLANT, EPOCH_US, PERIOD_US, DELAY_US
    s.delay_compensation, s.watchdog_periods = True, WATCHDOG_PERIODS
    s.plant_kind, s.velocity_source, s.filter_tf_s = s.PLANT_UNICYCLE, s.VELOCITY_FROM_POSE, defaults.FILTER_TF_S
    s.gain_kp, s.gain_kd = defaults.GAIN_KP, defaults.GAIN_KD
    s.omega_max_radps, s.accel_max_mps2 = defaults.OMEGA_MAX_RADPS, defaults.ACCEL_MAX_MPS2
    s.speed_max_mps, s.min_speed_mps = defaults.SPEED_MAX_MPS, defaults.MIN_SPEED_MPS
    s.robot_count = 1
    robot = s.robot[0]
    robot.tracking_weight = [1.0, 1.0]
    robot.target.kind, robot.target.semi_axis_m = path_t.KIND_ELLIPSE, [3.0, 1.5]
    robot.target.omega_radps = 2 * math.pi / 10     # one lap in 10 s
    return s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--key-file", required=True, help="the bus's key (tools/keygen; mode 0600)")
    parser.add_argument("--lcm-url", default=None, help="LCM URL (default: LCM's)")
    parser.add_argument("--duration-s", type=float, default=20.0, help="plant time to run (default: the demo's 20 s)")
    args = parser.parse_args()
    plant, robot = Plant(args.lcm_url, auth.read_key_file(args.key_file)), Robot()
    session = demo_session(plant.session_id)
    ack = plant.request(session, session.ACTION_START, robot.now_us)
    if ack is None or ack.status != 0:
        sys.exit(f"plant.py: START {why_not(plant, ack)}")
    restarts, unanswered, ran = 0, 0, True
    for n in range(round(args.duration_s * 1e6) // PERIOD_US):
        # rule 3: sample n, taken tau before period n + 1's apply instant, serves it
        plant.next = robot.advance_to(EPOCH_US + (n + 1) * PERIOD_US - DELAY_US, plant.next)
        sample = unicycle_sample_t()
        sample.header.utime, sample.header.session_id, sample.header.sequence = robot.now_us, plant.session_id, n
        sample.has = sample.HAS_HEADING | sample.HAS_SPEED
        sample.position_m = [robot.x, robot.y]
        sample.heading_rad, sample.speed_mps = math.remainder(robot.heading, 2 * math.pi), robot.v
        plant.sent, plant.answered = n, False
        plant.publish(wire.SAMPLE, sample)
        deadline = time.monotonic() + ANSWER_WAIT_S
        while not plant.answered and not plant.restart and time.monotonic() < deadline:
            plant.lc.handle_timeout(10)
        unanswered = 0 if plant.answered else unanswered + 1
        if plant.restart or unanswered >= WATCHDOG_PERIODS:   # rule 5: stop the robot, START again
            print(f"plant.py: sample {n}: " + ("the node restarted or dropped our session: a new START" if plant.restart
                  else f"{unanswered} samples unanswered: the same START again"), file=sys.stderr)
            robot.stop()
            plant.next, unanswered, restarts = None, 0, restarts + 1
            if plant.restart:           # a new boot, or our session gone: a fresh session naming it
                session.session_id = plant.session_id = (plant.session_id + 1) & 0x7FFFFFFF
            ack = plant.request(session, session.ACTION_START, robot.now_us)
            if ack is None or ack.status != 0:   # the same START (a silent node), or the new one, not taken
                print(f"plant.py: START again: {why_not(plant, ack)}", file=sys.stderr)
                ran = False
                break
        plant.next = robot.advance_to(EPOCH_US + (n + 1) * PERIOD_US, plant.next)
    target = session.robot[0].target      # the ellipse, centred at 0: where it is now
    phase = target.omega_radps * (robot.now_us - EPOCH_US) * 1e-6
    error = math.hypot(robot.x - target.semi_axis_m[0] * math.cos(phase),
                       robot.y - target.semi_axis_m[1] * math.sin(phase))
    print(f"final_error_m={error:.6g} restarts={restarts} dropped_frames={plant.dropped}")
    plant.request(session, session.ACTION_STOP, robot.now_us)   # rule 6
    return 0 if ran else 1


if __name__ == "__main__":
    sys.exit(main())
