#!/usr/bin/env python3
"""Venues drawn at random from the color issue's ranges, one frame each.

    scripts/random_venues.py FIRST LAST [--extreme] [--dotvision BIN] [--work DIR]

For each seed: a scene YAML (the top-down preset's camera at half size,
8 + 8 robots, a ball anywhere in view, a random cast, saturation, gamma,
exposure, uneven light, marker shades and, in 30 % of them, a sun patch
over the ball), then `dotvision synth`, `run --robot-height 140` and
`eval`. Prints one row per seed; rows below 1.000 are what to look at.
--extreme widens exposure to 1.4 and uneven light to 3 : 1.
"""
import argparse
import json
import os
import random
import subprocess
import sys


def lerp(a, b, t):
    return [round(a[i] + (b[i] - a[i]) * t) for i in range(3)]


def scene(seed, extreme):
    r = random.Random(seed)
    t, tilt = r.random(), r.uniform(-0.2, 0.2)
    wb = [1.6 + (0.7 - 1.6) * t, 1.0 + tilt, 0.6 + (1.7 - 0.6) * t]  # tungsten .. cold LED
    sat, gamma = r.uniform(0.4, 1.3), r.uniform(0.6, 1.6)
    exposure = r.uniform(0.8, 1.4 if extreme else 1.15)
    uneven, direction = r.uniform(1, 3 if extreme else 2.2), r.uniform(-3.14, 3.14)
    shades = {
        "pink": lerp((255, 140, 190), (230, 40, 160), r.random()),  # light rose .. magenta
        "green": lerp((150, 210, 50), (30, 170, 140), r.random()),  # yellow-green .. teal
        "yellow": lerp((240, 240, 80), (250, 165, 0), r.random()),  # lemon .. amber
        "blue": lerp((90, 170, 240), (20, 40, 130), r.random()),  # sky .. navy
        "ball": lerp((255, 120, 20), (240, 70, 20), r.random()),  # orange .. red-orange
    }
    bx, by = r.uniform(-3900, -600), r.uniform(-2400, 2400)
    sun = r.random() < 0.3
    lines = [
        f"name: venue_{seed}", f"seed: {seed}", "field: division_b", "cameras:",
        "  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 1750,",
        "     distortion: 0.03, principal_offset: [6.5, -4.0], size: [2448, 2048]}",
        f"ball: {{position: [{bx:.0f}, {by:.0f}]}}",
        f"random_robots: {{yellow: 8, blue: 8, camera: 0, margin_px: 60, seed: {seed}}}",
        "materials:",
    ] + [f"  {k}: [{v[0]}, {v[1]}, {v[2]}]" for k, v in shades.items()] + [
        "lighting:",
        f"  white_balance: [{wb[0]:.2f}, {wb[1]:.2f}, {wb[2]:.2f}]",
        f"  saturation: {sat:.2f}", f"  gamma: {gamma:.2f}", f"  exposure: {exposure:.2f}",
        f"  uneven_ratio: {uneven:.2f}", f"  uneven_direction: {direction:.2f}",
    ]
    if sun:
        gain = r.uniform(1.5, 2.3)
        lines += ["  sun_patches:",
                  f"    - {{center: [{bx:.0f}, {by:.0f}], radii: [600, 500], angle: 0.3, gain: {gain:.2f}, softness: 0.25}}"]
    lines += ["noise_sigma: 1.5", "shot_noise: 0.05", "lens_blur_px: 0.6", "antialias: 2", "frames: 1", "bayer: true"]
    desc = (f"wb {wb[0]:.2f},{wb[1]:.2f},{wb[2]:.2f} sat {sat:.2f} gamma {gamma:.2f} exposure {exposure:.2f} "
            f"uneven {uneven:.1f} sun {'yes' if sun else 'no'} "
            + " ".join(f"{k}{tuple(v)}".replace(" ", "") for k, v in shades.items()))
    return "\n".join(lines) + "\n", desc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("first", type=int)
    ap.add_argument("last", type=int)
    ap.add_argument("--extreme", action="store_true")
    ap.add_argument("--dotvision", default=os.path.join(os.path.dirname(__file__), "..", "build", "dotvision"))
    ap.add_argument("--work", default="random_venues")
    a = ap.parse_args()
    for seed in range(a.first, a.last + 1):
        yaml, desc = scene(seed, a.extreme)
        d = os.path.join(a.work, f"venue_{seed}")
        os.makedirs(d, exist_ok=True)
        with open(d + ".yaml", "w") as f:
            f.write(yaml)
        run = lambda *args: subprocess.run([a.dotvision, *args], capture_output=True, text=True)
        if run("synth", d + ".yaml", "--scale", "0.5", "--out", d).returncode != 0:
            print(f"{seed}: synth failed", file=sys.stderr)
            continue
        det = os.path.join(d, "detections.jsonl")
        run("run", "--source", d, "--geometry", os.path.join(d, "geometry.json"), "--camera-id", "0",
            "--robot-height", "140", "--no-publish", "--quiet", "--jsonl", det)
        out = run("eval", "--json", "--truth", os.path.join(d, "truth.jsonl"), "--detections", det).stdout
        o = json.loads(out[out.find("{"):])["overall"]
        rb, bl = o["robots"], o["balls"]
        print(f"{seed:4d} robots {rb['recall']:.3f} precision {rb['precision']:.3f} ids {rb['id_accuracy']:.3f} "
              f"ball {bl['recall']:.3f} false balls {bl['false_positives']} | {desc}", flush=True)


if __name__ == "__main__":
    main()
