#!/usr/bin/env python3
"""Writes the scripted sensor samples of tests/graphs/expect_fusion_*.json: a car driving straight
along +x at 20 m/s for 4 s, heading 0, its GNSS antennas at base_link (the graphs set antenna0
and antenna1 to [0, 0, 0]). Receiver 1 of the faulty script reads 3 m to the left from 2.0 s to
3.0 s. The truth (VehicleState, 100 Hz) is what the estimate is checked against. Run from this folder; the outputs are committed beside it."""
import json

V, T = 20.0, 4.0


def header(t, frame):
    return {"stamp_ns": round(t * 1e9), "frame_id": frame}


def write(name, samples):
    with open(name, "w") as f:
        f.write("[\n" + ",\n".join(json.dumps(s, separators=(",", ":")) for s in samples) + "\n]\n")


def fixes(receiver, jump=None):
    out = []
    for k in range(int(T * 10) + 1):
        t = round(0.1 * k, 3)
        y = 3.0 if jump and jump[0] <= t < jump[1] else 0.0
        out.append({"t": t, "msg": {"header": header(t, "map"), "receiver_id": receiver, "x": V * t, "y": y,
                                    "sigma_x": 0.02, "sigma_y": 0.02, "sigma_z": 0.05, "fix_type": 3, "valid": True}})
    return out


imu = [{"t": round(0.01 * k, 3), "msg": {"header": header(0.01 * k, "imu"), "accel_z": 9.81}} for k in range(int(T * 100) + 1)]
wheels = [{"t": round(0.01 * k, 3), "msg": {"header": header(0.01 * k, "vehicle"), "front_left": V, "front_right": V,
                                            "rear_left": V, "rear_right": V}} for k in range(int(T * 100) + 1)]
truth = [{"t": round(0.01 * k, 3), "msg": {"header": header(0.01 * k, "map"), "x": V * 0.01 * k, "vx": V}} for k in range(int(T * 100) + 1)]
write("straight_truth.json", truth)
write("straight_imu.json", imu)
write("straight_wheels.json", wheels)
write("straight_gnss0.json", fixes(0))
write("straight_gnss1.json", fixes(1))
write("straight_gnss1_jump.json", fixes(1, (2.0, 3.0)))
