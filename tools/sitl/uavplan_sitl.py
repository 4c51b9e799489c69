#!/usr/bin/env python3
"""Flies ArduPilot missions in ArduPilot's SITL, one simulator per UAV, side by side.

Called by `uavplan fly` (apps/uavplan/cmd_fly.cpp), which exports the missions and reads back
the tracks. For each UAV of the schedule: a SITL instance (ArduCopter's quad, or ArduPlane's plane for a
fixed wing, lined up with its take-off) in its own folder under --work with its home at the
mission's row 0, the mission uploaded over MAVLink (its own TCP port), armed and
started in AUTO; GLOBAL_POSITION_INT recorded on the simulator's own clock until the vehicle has
landed and disarmed (or the flight limit passes). Each track is written as
--out/<file stem>.csv: `t_s,lat_deg,lon_deg,alt_amsl_m`, t_s in simulated seconds since its
mission started. Each vehicle keeps its own simulated clock, so the tracks are aligned by the
schedule: a mission started at its scheduled moment of one common clock (as GPS time gives
real vehicles).

The MAVLink codec is pymavlink's: the installed `ardupilotmega` dialect where it imports, else
one generated from the ardupilotmega.xml found under --sitl with pymavlink's generator.
Only Debian's python3 is needed besides. Exit 0 when every vehicle flew its mission to the end.
"""

import argparse
import contextlib
import csv
import glob
import json
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

AUTO_MODE = {'multirotor': 3, 'fixed_wing': 10}  # ArduCopter's and ArduPlane's custom mode AUTO
MAV_MODE_FLAG_CUSTOM_MODE_ENABLED = 1
MAV_MODE_FLAG_SAFETY_ARMED = 128


def load_codec(sitl_dir, work):
    """The ardupilotmega MAVLink module: installed, else generated from the SITL folder's XML."""
    sys.path.insert(0, os.path.join(sitl_dir, 'python'))
    try:
        from pymavlink.dialects.v20 import ardupilotmega  # noqa: F401  (an installed dialect)
        return ardupilotmega
    except Exception:  # a source checkout without a generated dialect
        pass
    xmls = sorted(glob.glob(os.path.join(sitl_dir, '**', 'ardupilotmega.xml'), recursive=True),
                  key=lambda p: ('message_definitions' not in p, len(p)))
    if not xmls:
        sys.exit('uavplan_sitl: no ardupilotmega.xml under %s to build the MAVLink codec from' % sitl_dir)
    from pymavlink.generator import mavgen
    src = os.path.dirname(xmls[0])
    gen = os.path.join(work, 'mavlink')
    os.makedirs(gen, exist_ok=True)
    for xml in glob.glob(os.path.join(src, '*.xml')):
        shutil.copy(xml, gen)
    out = os.path.join(gen, 'ardupilotmega_codec.py')
    opts = mavgen.Opts(out, wire_protocol='2.0', language='Python3')
    with open(os.devnull, 'w') as quiet, contextlib.redirect_stdout(quiet):  # the generator's progress
        made = mavgen.mavgen(opts, [os.path.join(gen, 'ardupilotmega.xml')])
    if not made:
        sys.exit('uavplan_sitl: the MAVLink codec could not be generated from %s' % xmls[0])
    sys.path.insert(0, gen)
    import ardupilotmega_codec
    return ardupilotmega_codec


def read_wpl(path):
    """QGC WPL 110 rows: (seq, current, frame, command, p1..p4, x, y, z, autocontinue)."""
    rows = []
    with open(path) as f:
        if not f.readline().startswith('QGC WPL 110'):
            raise ValueError('%s: not a QGC WPL 110 file' % path)
        for line in f:
            v = line.split('\t')
            if len(v) >= 12:
                rows.append([int(v[0]), int(v[1]), int(v[2]), int(v[3])] + [float(x) for x in v[4:11]] + [int(v[11])])
    return rows


class Terrain(object):
    """Heights above sea level on a latitude-longitude grid (uavplan fly's terrain.json), read
    bilinearly: the ground the simulators fly over, sent to each autopilot as it asks for it."""

    SCALE_INV = 89.83204953368922  # ArduPilot's 1e7 degrees per metre (Location::offset)

    def __init__(self, path):
        with open(path) as f:
            j = json.load(f)
        self.lat0, self.lat1, self.lon0, self.lon1 = j['lat0'], j['lat1'], j['lon0'], j['lon1']
        self.rows, self.cols, self.h = j['rows'], j['cols'], j['heights_amsl']

    def height(self, lat, lon):
        fi = min(max((lat - self.lat0) / (self.lat1 - self.lat0) * (self.rows - 1), 0.0), self.rows - 1.0)
        fj = min(max((lon - self.lon0) / (self.lon1 - self.lon0) * (self.cols - 1), 0.0), self.cols - 1.0)
        i, j = min(int(fi), self.rows - 2), min(int(fj), self.cols - 2)
        u, v = fi - i, fj - j
        at = lambda a, b: self.h[a * self.cols + b]
        return ((1 - u) * ((1 - v) * at(i, j) + v * at(i, j + 1)) + u * ((1 - v) * at(i + 1, j) + v * at(i + 1, j + 1)))

    def blocks(self, lat_e7, lon_e7, spacing_m, mask):
        """TERRAIN_DATA for the requested 4 x 4 blocks: (gridbit, 16 heights), as ArduPilot lays
        a grid out (8 x 7 blocks; a block's rows north, its columns east of its corner)."""
        out = []
        scale = math.cos(math.radians(lat_e7 * 1e-7))
        for bit in range(56):
            if not mask & (1 << bit):
                continue
            data = []
            for k in range(16):
                north = spacing_m * (4 * (bit // 8) + k // 4)
                east = spacing_m * (4 * (bit % 8) + k % 4)
                lat = (lat_e7 + north * self.SCALE_INV) * 1e-7
                lon = (lon_e7 + east * self.SCALE_INV / scale) * 1e-7
                data.append(int(round(self.height(lat, lon))))
            out.append((bit, data))
        return out


class Vehicle(object):
    """One SITL instance and its MAVLink connection; fly() runs in its own thread."""

    def __init__(self, codec, args, uav, instance):
        self.m = codec
        self.args = args
        self.id = uav['id']
        missions = [f for f in uav['files'] if f.endswith('.waypoints')]
        if not missions:
            raise ValueError('%s: no .waypoints file in the schedule' % self.id)
        self.stem = os.path.splitext(os.path.basename(missions[0]))[0]
        self.limit_s = float(uav['flight_s']) * 2.0 + 120.0
        self.vehicle = uav.get('vehicle', 'multirotor')  # ArduCopter, or ArduPlane for a fixed wing
        self.parameters = uav.get('parameters', {})  # what the schedule's timing assumes
        self.instance = instance
        self.rows = read_wpl(os.path.join(args.missions, self.stem + '.waypoints'))
        self.dir = os.path.join(args.work, 'uav%d' % instance)
        os.makedirs(self.dir, exist_ok=True)
        self.proc = None
        self.sock = None
        self.mav = codec.MAVLink(None, srcSystem=255, srcComponent=190)
        self.mav.robust_parsing = True
        self.track = []
        self.error = None
        self.armed = False
        self.t_boot_ms = 0
        self.last = {}

    def pitot_ratio(self):
        """ARSPD_RATIO for the simulated plane's pitot. SITL's sensor reads the true airspeed
        divided by EAS2TAS twice (ArduPlane 4.7's SITL: measured, 7 % low at 700 m), so the
        autopilot holding an equivalent airspeed flies EAS2TAS too fast; the ratio calibrates it
        (by EAS2TAS squared, at the mission's mean altitude above sea level) as a pre-flight
        airspeed calibration would a real sensor."""
        home = self.rows[0][10]
        alts = [r[10] + (home if r[2] in (3, 10) else 0.0) for r in self.rows[1:] if r[3] == 16]
        h = sum(alts) / len(alts) if alts else home
        eas2tas_sq = (1.0 - 2.25577e-5 * min(max(h, -1000.0), 11000.0)) ** -4.2559
        return 1.9936 * eas2tas_sq  # ArduPlane's default ARSPD_RATIO

    # -- the simulator
    def start(self):
        home = self.rows[0]
        plane = self.vehicle == 'fixed_wing'
        # A fixed wing stands on its runway, lined up with its take-off (NAV_TAKEOFF's yaw).
        hdg = next((r[7] for r in self.rows[1:] if r[3] == 22), 0.0) if plane else 0.0
        cmd = [os.path.join(self.args.sitl, 'bin', 'arduplane' if plane else 'arducopter'),
               '--model', 'plane' if plane else 'quad', '--home',
               '%.9f,%.9f,%.3f,%.1f' % (home[8], home[9], home[10], hdg), '--speedup', str(self.args.speedup),
               '-I', str(self.instance), '--wipe']
        parm = os.path.join(self.args.sitl, 'params', 'plane.parm' if plane else 'copter.parm')
        if os.path.exists(parm):
            cmd += ['--defaults', parm]
        self.log = open(os.path.join(self.dir, 'sitl.log'), 'wb')
        self.messages = open(os.path.join(self.dir, 'messages.txt'), 'w')
        self.proc = subprocess.Popen(cmd, cwd=self.dir, stdout=self.log, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, start_new_session=True)

    def stop(self):
        if self.sock:
            self.sock.close()
        if getattr(self, 'messages', None):
            self.messages.close()
        if self.proc and self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait(5)

    # -- MAVLink
    def connect(self, timeout=60.0):
        port = 5760 + 10 * self.instance
        t0 = time.time()
        while time.time() - t0 < timeout:
            if self.proc.poll() is not None:
                raise RuntimeError('SITL exited (%s) during start-up' % self.proc.returncode)
            try:
                self.sock = socket.create_connection(('127.0.0.1', port), 1.0)
                self.sock.settimeout(0.2)
                return
            except OSError:
                time.sleep(0.3)
        raise RuntimeError('SITL did not open port %d' % port)

    def send(self, msg):
        self.sock.sendall(msg.pack(self.mav))

    def make(self, name, **fields):
        """A message by its fields' names (those a dialect lacks, such as newer extensions, left out)."""
        cls = getattr(self.m, 'MAVLink_%s_message' % name)
        names = cls.fieldnames
        return cls(*[fields.get(n, 0) for n in names])

    def pump(self):
        """Reads what has come; returns the messages."""
        try:
            data = self.sock.recv(65536)
        except socket.timeout:
            return []
        if not data:
            raise RuntimeError('SITL closed the connection')
        msgs = self.mav.parse_buffer(data) or []
        for msg in msgs:
            t = msg.get_type()
            self.last[t] = msg
            if t == 'HEARTBEAT' and msg.type != 6:  # not a GCS
                self.armed = bool(msg.base_mode & MAV_MODE_FLAG_SAFETY_ARMED)
            elif t == 'TERRAIN_REQUEST' and self.args.terrain_grid:
                for bit, data in self.args.terrain_grid.blocks(msg.lat, msg.lon, msg.grid_spacing, msg.mask):
                    self.send(self.make('terrain_data', lat=msg.lat, lon=msg.lon, grid_spacing=msg.grid_spacing,
                                        gridbit=bit, data=data))
            elif t == 'STATUSTEXT':  # the autopilot's messages, for a flight that goes wrong
                self.messages.write('%.1f %s\n' % (self.t_boot_ms / 1000.0, msg.text))
            elif t == 'GLOBAL_POSITION_INT':
                self.t_boot_ms = msg.time_boot_ms
                if self.t_auto_ms is not None:
                    self.track.append(((msg.time_boot_ms - self.t_auto_ms) / 1000.0, msg.lat / 1e7, msg.lon / 1e7,
                                       msg.alt / 1000.0))
        return msgs

    def wait_for(self, pred, timeout, what):
        t0 = time.time()
        while time.time() - t0 < timeout:
            for msg in self.pump():
                r = pred(msg)
                if r is not None:
                    return r
            self.heartbeat()
        raise RuntimeError('no %s within %.0f s' % (what, timeout))

    def heartbeat(self):
        now = time.time()
        if now - getattr(self, '_hb', 0.0) >= 1.0:
            self._hb = now
            self.send(self.make('heartbeat', type=6, autopilot=8, mavlink_version=3))

    def command(self, cmd, params, timeout=5.0):
        p = list(params) + [0] * (7 - len(params))
        self.send(self.make('command_long', target_system=1, target_component=1, command=cmd, param1=p[0],
                            param2=p[1], param3=p[2], param4=p[3], param5=p[4], param6=p[5], param7=p[6]))
        return self.wait_for(lambda m: m.result if m.get_type() == 'COMMAND_ACK' and m.command == cmd else None,
                             timeout, 'answer to command %d' % cmd)

    def set_param(self, name, value):
        self.send(self.make('param_set', target_system=1, target_component=1, param_id=name.encode(),
                            param_value=float(value), param_type=9))
        self.wait_for(lambda m: True if m.get_type() == 'PARAM_VALUE' and m.param_id == name else None, 10,
                      'PARAM_VALUE %s' % name)

    def upload(self):
        n = len(self.rows)
        self.send(self.make('mission_count', target_system=1, target_component=1, count=n))
        sent = set()
        t0 = time.time()
        while time.time() - t0 < 60:
            for msg in self.pump():
                t = msg.get_type()
                if t in ('MISSION_REQUEST_INT', 'MISSION_REQUEST'):
                    r = self.rows[msg.seq]
                    self.send(self.make('mission_item_int', target_system=1, target_component=1, seq=r[0],
                                        frame=r[2], command=r[3], current=1 if r[0] == 0 else 0,
                                        autocontinue=r[11], param1=r[4], param2=r[5], param3=r[6], param4=r[7],
                                        x=int(round(r[8] * 1e7)), y=int(round(r[9] * 1e7)), z=r[10]))
                    sent.add(msg.seq)
                elif t == 'MISSION_ACK':
                    if msg.type != 0:
                        raise RuntimeError('mission refused (MISSION_ACK type %d) after %d of %d items'
                                           % (msg.type, len(sent), n))
                    return
                elif t == 'STATUSTEXT' and 'support' in msg.text:
                    raise RuntimeError(msg.text)
            self.heartbeat()
        raise RuntimeError('mission upload timed out')

    # -- the flight
    def fly(self):
        try:
            self.t_auto_ms = None
            self.connect()
            self.heartbeat()
            # Positions at 10 Hz of the simulated clock (MAV_CMD_SET_MESSAGE_INTERVAL, 511).
            self.wait_for(lambda m: True if m.get_type() == 'HEARTBEAT' else None, 60, 'heartbeat')
            self.command(511, [33, 100000])
            if self.vehicle == 'fixed_wing':
                self.set_param('LAND_DISARMDELAY', 3)  # disarmed 3 s after it has stopped (default 20)
                self.set_param('ARSPD_RATIO', self.pitot_ratio())
            else:
                self.set_param('AUTO_OPTIONS', 3)  # arm in AUTO, take off without a pilot's throttle
                # The simulated quad reaches about 10.5 m/s at ArduCopter's default lean limit (30
                # deg), 13.5 m/s at 45 deg; 60 deg for a mission commanding more than 12 m/s (at
                # 60 deg the corners of slower missions are rounded wider).
                fast = any(r[3] == 178 and r[5] > 12.0 for r in self.rows)
                self.set_param('ANGLE_MAX', 6000 if fast else 4500)
            for name, value in sorted(self.parameters.items()):
                self.set_param(name, value)
            if self.args.terrain_grid:  # the ground sent at 30 m (ArduPilot's default 100 m is coarse)
                self.set_param('TERRAIN_SPACING', 30)
                self.command(511, [133, 200000])  # TERRAIN_REQUEST at up to 5 Hz (none by default on TCP)
            # A position first: the vehicle has settled enough to take a mission.
            self.wait_for(lambda m: True if m.get_type() == 'GLOBAL_POSITION_INT' and m.lat != 0 else None, 120,
                          'position')
            # Uploaded in real time: the autopilot re-sends a request it has no answer to within
            # a second of its own (simulated) clock, 50 ms of ours at 20x on a loaded machine, and
            # refuses the answers that then come out of order (MAV_MISSION_INVALID_SEQUENCE).
            self.set_param('SIM_SPEEDUP', 1)
            for attempt in range(5):
                try:
                    self.upload()
                    break
                except RuntimeError:
                    if attempt == 4:
                        raise
                    time.sleep(2.0)
            self.set_param('SIM_SPEEDUP', self.args.speedup)
            self.command(176, [MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, AUTO_MODE[self.vehicle]])
            t0 = time.time()
            while True:  # the pre-arm checks pass once GPS and the EKF have settled
                if self.command(400, [1]) == 0:
                    break
                if time.time() - t0 > 120:
                    raise RuntimeError('would not arm within 120 s')
                time.sleep(0.5)
            self.t_auto_ms = self.t_boot_ms
            landed_since = None
            while True:
                self.pump()
                self.heartbeat()
                flown = (self.t_boot_ms - self.t_auto_ms) / 1000.0
                if not self.armed and flown > 5.0:
                    if landed_since is None:
                        landed_since = flown
                    if flown - landed_since > 2.0:
                        break
                if flown > self.limit_s:
                    raise RuntimeError('still flying after %.0f s (the limit)' % self.limit_s)
        except Exception as e:  # reported per vehicle, the others fly on
            self.error = str(e)

    def write(self, path):
        with open(path, 'w', newline='') as f:
            w = csv.writer(f)
            w.writerow(['t_s', 'lat_deg', 'lon_deg', 'alt_amsl_m'])
            for row in self.track:
                w.writerow(['%.3f' % row[0], '%.9f' % row[1], '%.9f' % row[2], '%.3f' % row[3]])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--sitl', required=True, help='the SITL folder (bin/arducopter or bin/arduplane, params/, python/)')
    ap.add_argument('--missions', required=True, help='the folder of the .waypoints files and schedule.json')
    ap.add_argument('--out', required=True, help='where the tracks are written')
    ap.add_argument('--work', required=True, help='a scratch folder (the simulators run there)')
    ap.add_argument('--speedup', type=float, default=10.0)
    ap.add_argument('--first-instance', type=int, default=0)
    ap.add_argument('--terrain', help='the ground under the flights (terrain.json); else a plane at each home')
    args = ap.parse_args()
    for name in ('sitl', 'missions', 'out', 'work', 'terrain'):  # the simulators run in folders of their own
        if getattr(args, name):
            setattr(args, name, os.path.abspath(getattr(args, name)))
    args.terrain_grid = Terrain(args.terrain) if args.terrain else None
    codec = load_codec(args.sitl, args.work)
    with open(os.path.join(args.missions, 'schedule.json')) as f:
        schedule = json.load(f)
    vehicles = [Vehicle(codec, args, u, args.first_instance + i) for i, u in enumerate(schedule['uavs'])]
    try:
        for v in vehicles:
            v.start()
        threads = [threading.Thread(target=v.fly) for v in vehicles]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        for v in vehicles:
            v.stop()
    failed = 0
    for v in vehicles:
        v.write(os.path.join(args.out, v.stem + '.csv'))
        if v.error:
            failed += 1
            print('uavplan_sitl: %s: %s' % (v.id, v.error), file=sys.stderr)
        else:
            print('uavplan_sitl: %s flown, %d positions' % (v.id, len(v.track)), file=sys.stderr)
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
