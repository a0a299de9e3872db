#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""CARLA -> gnssemud: the ego vehicle's GNSS antenna as truth, every tick.

  carla_truth.py [--carla-host H] [--carla-port 2000] [--role-name hero | --actor-id ID]
                 [--host 127.0.0.1] [--port 5500] [--vehicle ego] [--antenna X Y Z] [--json]
  carla_truth.py --self-test        # conversions and record layout; needs no CARLA

Set gnssemud's [origin] to the CARLA map's geo-reference (the OpenDRIVE
<geoReference>; in CARLA world.get_map().transform_to_geolocation(
carla.Location(0, 0, 0))), so that local ENU means the same here and in the
daemon. The daemon's ENU is an exact tangent plane; CARLA's own GNSS sensor
projects differently (Mercator or transverse Mercator, by version), so the
two drift apart slowly with distance from the origin.

Frames:
- CARLA's world is Unreal's left-handed frame in metres, z up ("Coordinates
  and transformations", https://carla.readthedocs.io/en/latest/coordinates/).
  On the map +x points east and +y south: CARLA's geolocation feeds
  (location.x, -location.y) to its projection "to have increasing latitudes
  northward" (LibCarla/source/carla/geom/GeoLocation.cpp, CARLA 0.9.x).
  So (e, n, u) = (x, -y, z), for positions and for velocities.
- carla.Rotation is in degrees. Its RotateVector (LibCarla geom/Rotation.h)
  takes the vehicle's forward axis to (cos p cos y, cos p sin y, sin p) and
  its right axis to z = -cos p sin r: pitch is nose up, roll right side down,
  yaw turns from +x (east) towards +y (south), clockwise seen from above. The
  daemon's attitude (body forward-right-down against north-east-down) is then
  roll and pitch unchanged, heading = yaw + 90 deg; the self-test checks this
  axis by axis.
- --antenna is the antenna's offset in the vehicle frame (x forward, y right,
  z up, m, from the actor's origin near the ground). The velocity sent is the
  actor's; the lever arm's rotation term is left out, so with a horizontal
  offset no velocity is sent and the daemon differentiates positions instead.

Binary records by default (docs/truth-protocol.md §Binary record); --json
sends JSON, which carries no attitude. Stdlib only, besides the carla module.
"""
import argparse
import json
import math
import random
import socket
import struct
import sys
import time

RECORD = struct.Struct("<4sBBH64sdd3d3d3d")  # docs/truth-protocol.md §Binary record
MAGIC = b"\xf7GTR"
VERSION = 1
POS_ENU = 2
VEL_ENU = 1 << 2
HAS_ATTITUDE = 0x10
HAS_GPS_TIME = 0x20


# --- pure conversions (no CARLA) -----------------------------------------------

def carla_to_enu(v):
    """CARLA world vector (x east, y south, z up; m or m/s) -> local ENU."""
    return (v[0], -v[1], v[2])


def carla_rotate(rotation_deg, v):
    """A vehicle-frame vector in CARLA's world frame. rotation_deg: (roll,
    pitch, yaw) of a carla.Rotation; the same matrix as its RotateVector."""
    r, p, y = (math.radians(a) for a in rotation_deg)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return (v[0] * cp * cy + v[1] * (cy * sp * sr - sy * cr) + v[2] * (-cy * sp * cr - sy * sr),
            v[0] * cp * sy + v[1] * (sy * sp * sr + cy * cr) + v[2] * (-sy * sp * cr + cy * sr),
            v[0] * sp + v[1] * (-cp * sr) + v[2] * (cp * cr))


def _wrap_deg(a):
    """Angle in degrees wrapped to [-180, 180)."""
    return (a + 180.0) % 360.0 - 180.0


def carla_attitude(rotation_deg):
    """carla.Rotation (roll, pitch, yaw; deg) -> the daemon's attitude
    (roll [-pi, pi), pitch [-pi/2, pi/2], heading from north [0, 2 pi); rad)."""
    roll, pitch, yaw = (_wrap_deg(a) for a in rotation_deg)
    if abs(pitch) > 90.0:  # the same orientation with pitch inside +-90 deg
        pitch = math.copysign(180.0, pitch) - pitch
        roll, yaw = _wrap_deg(roll + 180.0), yaw + 180.0
    heading = (yaw + 90.0) % 360.0
    return (math.radians(roll), math.radians(pitch), math.radians(heading))


def antenna_truth(location_m, rotation_deg, velocity_m_s, antenna_m):
    """Antenna position (ENU m), velocity (ENU m/s or None) and attitude (rad)
    from the actor's location, rotation and velocity in CARLA's world frame.
    antenna_m: offset in the vehicle frame (x forward, y right, z up), m."""
    offset = carla_rotate(rotation_deg, antenna_m)
    pos = carla_to_enu(tuple(location_m[i] + offset[i] for i in range(3)))
    # The lever arm's rotation term is omitted: send a velocity only when
    # the offset is vertical (roll and pitch rates of a car are small).
    vertical = abs(antenna_m[0]) < 1e-9 and abs(antenna_m[1]) < 1e-9
    vel = carla_to_enu(velocity_m_s) if vertical else None
    return pos, vel, carla_attitude(rotation_deg)


def encode_record(vehicle, sim_time_s, enu_m, vel_enu_m_s=None, attitude_rad=None, gps_time=None):
    """One binary truth record (160 bytes). gps_time: (week, tow_s) or None."""
    vid = vehicle.encode()
    if not 1 <= len(vid) <= 64 or b"\0" in vid:
        raise ValueError("vehicle id: 1..64 bytes, no NUL")
    flags = POS_ENU | (VEL_ENU if vel_enu_m_s else 0) | (HAS_ATTITUDE if attitude_rad else 0) | \
        (HAS_GPS_TIME if gps_time else 0)
    week, tow = gps_time if gps_time else (0, 0.0)
    return RECORD.pack(MAGIC, VERSION, flags, week, vid, sim_time_s, tow, *enu_m,
                       *(vel_enu_m_s or (0.0, 0.0, 0.0)), *(attitude_rad or (0.0, 0.0, 0.0)))


def encode_json(vehicle, sim_time_s, enu_m, vel_enu_m_s=None):
    msg = {"version": 1, "vehicle": vehicle, "sim_time_s": sim_time_s,
           "enu": {"e_m": enu_m[0], "n_m": enu_m[1], "u_m": enu_m[2]}}
    if vel_enu_m_s:
        msg["vel_enu"] = {"e_m_s": vel_enu_m_s[0], "n_m_s": vel_enu_m_s[1], "u_m_s": vel_enu_m_s[2]}
    return json.dumps(msg, allow_nan=False).encode()


# --- self-test -------------------------------------------------------------------

# docs/truth-protocol.md worked example; the C++ encoder's test pins the same bytes.
GOLDEN_HEX = ("f747545201368e0865676f000000000000000000000000000000000000000000"
              "0000000000000000000000000000000000000000000000000000000000000000"
              "000000000000000000000000000029400000000002a41f410000000000005e40"
              "00000000000054c0000000000000f83f00000000000014400000000000000000"
              "000000000000000000000000000000000000000000000000182d4454fb21f93f")


def _ned_axes_enu(att):
    """Body forward, right and down axes of an attitude (rad), in ENU."""
    r, p, h = att
    cr, sr, cp, sp, ch, sh = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(h), math.sin(h)
    ned = ((ch * cp, sh * cp, -sp),
           (ch * sp * sr - sh * cr, sh * sp * sr + ch * cr, cp * sr),
           (ch * sp * cr + sh * sr, sh * sp * cr - ch * sr, cp * cr))
    return [(a[1], a[0], -a[2]) for a in ned]


def _close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def self_test():
    checks = 0

    def check(cond, what):
        nonlocal checks
        if not cond:
            raise AssertionError(what)
        checks += 1

    check(carla_to_enu((10.0, 20.0, 3.0)) == (10.0, -20.0, 3.0), "+y is south")
    # Heading: CARLA yaw 0 faces +x = east, 90 faces south, -90 north.
    for yaw, heading in ((0.0, 90.0), (90.0, 180.0), (-90.0, 0.0), (180.0, 270.0)):
        check(abs(math.degrees(carla_attitude((0.0, 0.0, yaw))[2]) - heading) < 1e-9, f"yaw {yaw}")
    # Axis by axis: CARLA's rotation, taken to ENU, is the attitude's rotation.
    rng = random.Random(13)
    for _ in range(500):
        rot = (rng.uniform(-200, 200), rng.uniform(-200, 200), rng.uniform(-400, 400))
        att = carla_attitude(rot)
        check(-math.pi <= att[0] < math.pi and abs(att[1]) <= math.pi / 2 and 0 <= att[2] < 2 * math.pi,
              f"attitude range {rot} -> {att}")
        fwd, right, down = _ned_axes_enu(att)
        check(_close(carla_to_enu(carla_rotate(rot, (1, 0, 0))), fwd), f"forward axis {rot}")
        check(_close(carla_to_enu(carla_rotate(rot, (0, 1, 0))), right), f"right axis {rot}")
        check(_close(carla_to_enu(carla_rotate(rot, (0, 0, 1))), tuple(-d for d in down)), f"up axis {rot}")
    # Lever arm: 1 m forward, 1.5 m up on a car facing north (yaw -90).
    pos, vel, _ = antenna_truth((100.0, -50.0, 0.2), (0.0, 0.0, -90.0), (0.0, -10.0, 0.0), (1.0, 0.0, 1.5))
    check(_close(pos, (100.0, 51.0, 1.7)), f"antenna position {pos}")
    check(vel is None, "no velocity with a horizontal lever arm")
    pos, vel, _ = antenna_truth((100.0, -50.0, 0.2), (0.0, 0.0, -90.0), (0.0, -10.0, 0.0), (0.0, 0.0, 1.5))
    check(_close(vel, (0.0, 10.0, 0.0)), f"velocity north {vel}")
    # Record layout: the documented worked example, byte for byte.
    rec = encode_record("ego", 12.5, (120.0, -80.0, 1.5), (5.0, 0.0, 0.0), (0.0, 0.0, math.pi / 2), (2190, 518400.5))
    check(len(rec) == 160 and rec.hex() == GOLDEN_HEX, "golden record")
    check(json.loads(encode_json("ego", 1.0, (1.0, 2.0, 3.0), (0.0, 1.0, 0.0)))["enu"]["n_m"] == 2.0, "json")
    print(f"carla_truth self-test: {checks} checks passed")


# --- CARLA -----------------------------------------------------------------------

def find_ego(world, args):
    vehicles = world.get_actors().filter("vehicle.*")
    if args.actor_id is not None:
        found = [a for a in vehicles if a.id == args.actor_id]
    else:
        found = [a for a in vehicles if a.attributes.get("role_name") == args.role_name]
    if not found:
        sys.exit(f"carla_truth: no vehicle with {'id ' + str(args.actor_id) if args.actor_id is not None else 'role_name ' + repr(args.role_name)}")
    return found[0]


def run(args):
    import carla  # only here: --self-test needs no CARLA

    client = carla.Client(args.carla_host, args.carla_port)
    client.set_timeout(10.0)
    world = client.get_world()
    ego = find_ego(world, args)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    dest = (args.host, args.port)
    antenna = tuple(args.antenna)
    print(f"carla_truth: {ego.type_id} (id {ego.id}) -> {dest[0]}:{dest[1]} as '{args.vehicle}'", flush=True)

    def on_tick(snapshot):
        actor = snapshot.find(ego.id)
        if actor is None:
            return
        tf = actor.get_transform()
        v = actor.get_velocity()
        pos, vel, att = antenna_truth((tf.location.x, tf.location.y, tf.location.z),
                                      (tf.rotation.roll, tf.rotation.pitch, tf.rotation.yaw),
                                      (v.x, v.y, v.z), antenna)
        t = snapshot.timestamp.elapsed_seconds
        data = encode_json(args.vehicle, t, pos, vel) if args.json else encode_record(args.vehicle, t, pos, vel, att)
        sock.sendto(data, dest)

    callback = world.on_tick(on_tick)
    try:
        while True:
            time.sleep(1.0)
    except KeyboardInterrupt:
        pass
    finally:
        world.remove_on_tick(callback)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--self-test", action="store_true", help="check the conversions without CARLA, then exit")
    p.add_argument("--carla-host", default="127.0.0.1")
    p.add_argument("--carla-port", type=int, default=2000)
    p.add_argument("--role-name", default="hero", help="role_name attribute of the ego vehicle")
    p.add_argument("--actor-id", type=int, help="ego vehicle by actor id instead")
    p.add_argument("--host", default="127.0.0.1", help="gnssemud truth address")
    p.add_argument("--port", type=int, default=5500)
    p.add_argument("--vehicle", default="ego", help="vehicle id sent to the daemon")
    p.add_argument("--antenna", type=float, nargs=3, default=(0.0, 0.0, 1.5), metavar=("X", "Y", "Z"),
                   help="antenna offset in the vehicle frame (forward, right, up), m")
    p.add_argument("--json", action="store_true", help="send JSON (no attitude) instead of binary records")
    args = p.parse_args()
    if args.self_test:
        self_test()
        return 0
    run(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
