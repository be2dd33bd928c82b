#!/usr/bin/env python3
"""Writes the scripted samples of tests/graphs/expect_road_graph_swerve.json: a car standing on
IMS's racing line on the front straight (230 m past the line's first point), its estimate at 50 Hz,
and an obstacle 1 m by 1 m about 70 m ahead of it on the path the planner makes with no obstacle
(pose 37 of that path, 1.6 m right of the centre line: the planner keeps the file's line 3.5 m
inside the edges, so its path is not the file's points), detected at 10 Hz (vehicle frame, stamped
at the estimate's instant). Run from this folder; the outputs are committed beside it."""
import csv
import json
import math

with open("../../../data/racelines/IMS.csv") as f:
    line = [(float(r[0]), float(r[1])) for r in csv.reader(f) if r and not r[0].startswith("#")]
car_i = 46  # the line's points are 5 m apart: 230 m along it
(cx, cy), (nx, ny) = line[car_i], line[car_i + 1]
yaw = math.atan2(ny - cy, nx - cx)
# poses[37] of planning.road_graph's path at 1 s in fail_expect_road_graph_no_obstacle.json
ox, oy = 4.433, -297.876
# The obstacle in the car's frame: x forward, y left.
fx = math.cos(yaw) * (ox - cx) + math.sin(yaw) * (oy - cy)
fy = -math.sin(yaw) * (ox - cx) + math.cos(yaw) * (oy - cy)
T = 3.0


def header(t, frame):
    return {"stamp_ns": round(t * 1e9), "frame_id": frame}


def write(name, samples):
    with open(name, "w") as f:
        f.write("[\n" + ",\n".join(json.dumps(s, separators=(",", ":")) for s in samples) + "\n]\n")


estimate = [{"t": round(0.02 * k, 3), "msg": {"header": header(0.02 * k, "map"), "x": cx, "y": cy, "yaw": yaw, "speed": 30.0,
                                              "covariance": [0.01, 0, 0, 0, 0.01, 0, 0, 0, 1e-4]}}
            for k in range(int(T * 50) + 1)]
obstacles = [{"t": round(0.1 * k, 3), "msg": {"header": header(0.1 * k, "base_link"), "obstacles": [
    {"x": fx, "y": fy, "z": 0.5, "size_x": 1.0, "size_y": 1.0, "size_z": 1.0, "point_count": 40}]}}
    for k in range(int(T * 10) + 1)]
write("ims_car_on_line.json", estimate)
write("ims_obstacle_ahead.json", obstacles)
print("car at (%.3f, %.3f) yaw %.4f; obstacle at map (%.3f, %.3f), vehicle (%.3f, %.3f)" % (cx, cy, yaw, ox, oy, fx, fy))
