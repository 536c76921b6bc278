#!/usr/bin/env python3
"""The seed's point light as the limit of a small glowing sphere, measured: the per-pixel relative difference
between a sphere light of radius R and the point light of the same intensity and position (GGX alpha 0.1 at
45 deg, both 10 from the origin, the eye on the mirror direction at 10), against R, with its order.

    PYTHONPATH=build/python /usr/bin/python3 examples/sphere_to_point.py docs/sphere_to_point.png

tests/render/test_area_lights_gl.cpp asserts the same order (1.9 to 2.1) from the same renders in C++.
"""
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import hilite

SCENE = dict(model="ggx", roughness=0.1, incidence=45, light_distance=10, distance=10, size=96, fov=40, view="measure")


def luminance(**extra):
    _, maps = hilite.render(maps=True, **SCENE, **extra)
    return maps["luminance"]


def main(out):
    point = luminance(light="point")
    mask = point > 1e-3 * point.max()
    radii = np.array([0.8, 0.4, 0.2, 0.1, 0.05, 0.025])
    errors = []
    for r in radii:
        sphere = luminance(light="sphere", light_radius=float(r), light_rings=8)
        errors.append(np.max(np.abs(sphere[mask] - point[mask]) / point[mask]))
    errors = np.array(errors)
    fit = radii <= 0.4  # the asymptotic range: higher orders show at R = 0.8 (alpha = 4.6 deg)
    order, logc = np.polyfit(np.log(radii[fit]), np.log(errors[fit]), 1)
    for r, e in zip(radii, errors):
        print(f"R = {r:6.3f}: max per-pixel relative error {e:.3e}")
    print(f"order (R <= 0.4): {order:.3f}")
    plt.figure(figsize=(6.4, 4.2))
    plt.loglog(radii, errors, "o-", label="sphere vs point light, max over pixels")
    plt.loglog(radii, np.exp(logc) * radii**order, "--", label=f"fit: order {order:.2f}")
    plt.loglog(radii, errors[-1] * (radii / radii[-1]) ** 2, ":", label="R^2")
    plt.xlabel("sphere radius R (distance 10)")
    plt.ylabel("max per-pixel relative error")
    plt.title("The point light as the limit of a glowing sphere (GGX 0.1, 45 deg)")
    plt.grid(True, which="both", alpha=0.3)
    plt.legend()
    plt.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)  # the output's folder, made if missing
    plt.savefig(out, dpi=100)
    plt.close()
    return order


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sphere_to_point.png")
