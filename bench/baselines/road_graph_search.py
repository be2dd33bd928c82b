#!/usr/bin/env python3
"""The Python reference for bench_planning: the same road-graph search as
plugins/planning/common/graph_search.cpp, written plainly in Python (what a team's first planner
often is; TUM's graph planner is Python too), on the same graph file and the same queries.

usage: road_graph_search.py GRAPH.byrg QUERIES.json  ->  one JSON line per query:
       {"ms": time of the search, "nodes": [the chosen path's nodes]}

The file format is documented in docs/planning.md (little-endian): format version 2, whose last
eight bytes are an FNV-1a digest of every byte before them, checked here as the C++ loader does."""
import json
import math
import struct
import sys
import time


FORMAT_VERSION = 2


def fnv1a(data):
    """FNV-1a, 64 bit (libs/math/fnv1a.hpp)."""
    h = 1469598103934665603
    for byte in data:
        h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def load(path):
    with open(path, "rb") as f:
        b = f.read()
    if b[:4] != b"BYRG":
        sys.exit(f"{path}: not a road graph")
    (version,) = struct.unpack_from("<I", b, 4)
    if version != FORMAT_VERSION:
        sys.exit(f"{path}: format version {version}, this reference reads {FORMAT_VERSION}")
    (digest,) = struct.unpack_from("<Q", b, len(b) - 8)
    if fnv1a(b[:-8]) != digest:
        sys.exit(f"{path}: its digest does not match its bytes")
    o = 8
    params = struct.unpack_from("<8d", b, o)
    o += 64
    o += 8  # digest
    (length,) = struct.unpack_from("<d", b, o)
    o += 8

    def array(fmt, size):
        nonlocal o
        (n,) = struct.unpack_from("<Q", b, o)
        o += 8
        items = list(struct.iter_unpack("<" + fmt, b[o:o + n * size]))
        o += n * size
        return items

    layers = array("diIII", 24)
    first_edge = [x[0] for x in array("I", 4)]
    edges = array("Iffff", 20)
    if o != len(b) - 8:
        sys.exit(f"{path}: {len(b) - 8 - o} bytes between the edges and the digest")
    node_layer = []
    for i, (_, _, count, _, _) in enumerate(layers):
        node_layer += [i] * count
    keys = ["layer_spacing", "layer_spacing_turn", "turn_curvature", "lateral_step", "half_width",
            "edge_margin", "max_curvature", "max_edge_length"]
    return dict(zip(keys, params)), length, layers, first_edge, edges, node_layer


def smooth_d(sa, da, sb, db, s):
    t = min(max((s - sa) / (sb - sa), 0.0), 1.0)
    return da + (db - da) * t * t * t * (10 - 15 * t + 6 * t * t)


def relative_s(s, s0, length):
    r = math.fmod(s - s0, length)
    if r < 0:
        r += length
    return r - length if r > 0.5 * length else r


def search(graph, q):
    params, length, layers, first_edge, edges, node_layer = graph
    p = q["params"]
    step, hw, reach = params["lateral_step"], params["half_width"], params["max_edge_length"]

    def node_s(n):
        return layers[node_layer[n]][0]

    def node_d(n):
        s, k0, count, first, _ = layers[node_layer[n]]
        return (k0 + (n - first)) * step

    start = q["start"]
    horizon = min(p["horizon"], length - reach - 1.0)
    s0 = node_s(start)
    near = []
    for o in q["obstacles"]:
        r = relative_s(o["s"], s0, length)
        if -p["car_rear"] - o["radius"] - 1 < r < horizon + reach + p["car_front"] + o["radius"] + 1:
            near.append((r, o["d"], o["radius"]))

    def rel(layer):
        r = layers[layer][0] - s0
        return r + length if r < 0 else r

    cost = {start: 0.0}
    parent = {start: None}
    l0 = node_layer[start]
    for off in range(len(layers)):
        layer = (l0 + off) % len(layers)
        ra = 0.0 if off == 0 else rel(layer)
        if off > 0 and ra >= horizon:
            break
        _, _, count, first, _ = layers[layer]
        for n in range(first, first + count):
            if n not in cost:
                continue
            da = node_d(n)
            for e in range(first_edge[n], first_edge[n + 1]):
                to, elen, curv, dev, max_kappa = edges[e]
                # The half width the car's body sweeps on the edge (graph_search.hpp,
                # swept_half_width): its nose stands car_front² |κ| / 2 outside the arc.
                k = abs(max_kappa)
                swept = hw + 0.5 * p["car_front"] ** 2 * (k if k < 1.0 else 1.0)
                rb = rel(node_layer[to])
                if rb <= ra:
                    rb += length
                db = node_d(to)
                c = p["k_length"] * elen + p["k_curvature"] * curv + p["k_deviation"] * dev
                blocked = False
                for (os_, od, orad) in near:
                    w0 = max(ra, os_ - p["car_front"] - orad)
                    w1 = min(rb, os_ + p["car_rear"] + orad)
                    if w0 > w1:
                        continue
                    a, b = smooth_d(ra, da, rb, db, w0), smooth_d(ra, da, rb, db, w1)
                    lo, hi = min(a, b), max(a, b)
                    apart = lo - od if od < lo else (od - hi if od > hi else 0.0)
                    gap = apart - orad - swept
                    if gap < p["clearance"]:
                        blocked = True
                        break
                    if gap < p["soft_clearance"]:
                        c += p["k_proximity"] * (p["soft_clearance"] - gap) ** 2
                if blocked:
                    continue
                total = cost[n] + c
                if total < cost.get(to, math.inf):
                    cost[to] = total
                    parent[to] = n
    s_end = horizon + reach
    best, best_cost = None, math.inf
    for n, c in cost.items():
        rn = rel(node_layer[n])
        if rn < horizon or n == start:
            continue
        total = c + max(0.0, s_end - rn) * (p["k_length"] + p["k_deviation"] * abs(node_d(n)))
        if total < best_cost or (total == best_cost and n < best):
            best, best_cost = n, total
    path = []
    while best is not None:
        path.append(best)
        best = parent[best]
    return path[::-1]


def main():
    graph = load(sys.argv[1])
    with open(sys.argv[2]) as f:
        queries = json.load(f)
    for q in queries:
        t0 = time.perf_counter()
        nodes = search(graph, q)
        ms = (time.perf_counter() - t0) * 1e3
        print(json.dumps({"ms": ms, "nodes": nodes}), flush=True)


if __name__ == "__main__":
    main()
