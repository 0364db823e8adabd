# Renders the setup written by `stratus export-volume --json` with Mitsuba 3 and compares block
# averages with the reference's renders (`--reference-out`). Written and run by
# `cargo xtask mitsuba-check`.
import json
import sys

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
from mitsuba import ScalarTransform4f as T  # noqa: E402

setup_path, reference_path, spp, passes, block = sys.argv[1:6]
spp, passes, block = int(spp), int(passes), int(block)
setup = json.load(open(setup_path))
ref = json.load(open(reference_path))
w, h = setup["width"], setup["height"]
lo, hi = np.array(setup["box_min"]), np.array(setup["box_max"])
sigma_t = setup["sigma_s"] + setup["sigma_a"]
origin = np.array(setup["camera_position"])
forward = np.array(setup["camera_forward"])
up = np.array(setup["camera_up"])


def scene(integrator):
    return mi.load_dict({
        "type": "scene",
        "integrator": integrator,
        "sensor": {
            "type": "perspective",
            "fov": setup["fov_y_deg"],
            "fov_axis": "y",
            "to_world": T().look_at(origin=origin.tolist(), target=(origin + forward).tolist(),
                                    up=up.tolist()),
            "film": {"type": "hdrfilm", "width": w, "height": h, "pixel_format": "rgb",
                     "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        # Mitsuba's direction is the one light travels: away from the sun.
        "sun": {"type": "directional", "direction": [-c for c in setup["sun_direction"]],
                "irradiance": {"type": "rgb", "value": setup["sun_illuminance"]}},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": setup["sky_radiance"]}},
        "box": {
            "type": "cube",
            "to_world": T().translate(((lo + hi) / 2).tolist()).scale(((hi - lo) / 2).tolist()),
            "bsdf": {"type": "null"},
            "interior": {
                "type": "heterogeneous",
                "sigma_t": {"type": "gridvolume", "filename": setup["volume"],
                            "to_world": T().translate(lo.tolist()).scale((hi - lo).tolist())},
                "albedo": {"type": "constvolume", "value": setup["sigma_s"] / sigma_t},
                "scale": sigma_t,
                "phase": {"type": "hg", "g": setup["phase_g"]},
            },
        },
    })


def mitsuba_blocks(integrator):
    s = scene(integrator)
    # Mitsuba's image x runs along cross(forward, up) (look_at's "left" negated); the
    # reference's along camera_right.
    flip = np.dot(np.cross(forward, up), setup["camera_right"]) < 0
    per_pass = []
    for k in range(passes):
        img = np.array(mi.render(s, seed=1000 + k, spp=spp), dtype=np.float64)[:, :, :3]
        if flip:
            img = img[:, ::-1, :]
        per_pass.append(blocks(img))
    per_pass = np.array(per_pass)
    return per_pass.mean(axis=0), per_pass.std(axis=0, ddof=1) / np.sqrt(passes)


def blocks(img):
    nby, nbx = h // block, w // block
    return img[: nby * block, : nbx * block].reshape(nby, block, nbx, block, 3).mean(axis=(1, 3))


def reference_blocks(name):
    r = np.array(ref[name]["radiance"], dtype=np.float64).reshape(h, w, 4)
    se = np.array(ref[name]["std_error"], dtype=np.float64).reshape(h, w, 4)
    sky = np.array(ref["sky_radiance"])
    # The reference's radiance is the in-scattered light; the camera also sees the sky through
    # the medium (transmittance in alpha).
    total = r[:, :, :3] + r[:, :, 3:4] * sky
    var = se[:, :, :3] ** 2 + (se[:, :, 3:4] * sky) ** 2
    n = block * block
    nby, nbx = h // block, w // block
    v = var[: nby * block, : nbx * block].reshape(nby, block, nbx, block, 3).sum(axis=(1, 3))
    return blocks(total), np.sqrt(v) / n


ok = True
for name, label, integrator in [
    ("single", "single scattering (volpath, max_depth=2)", {"type": "volpath", "max_depth": 2}),
    ("all", "all orders (volpathmis, max_depth=-1)", {"type": "volpathmis", "max_depth": -1}),
]:
    m, m_se = mitsuba_blocks(integrator)
    r, r_se = reference_blocks(name)
    se = np.sqrt(m_se ** 2 + r_se ** 2)
    rel = (r - m) / m
    z = np.where(se > 0, (r - m) / np.where(se > 0, se, 1.0), 0.0)
    print(f"\n{label}: {block}x{block} blocks, Mitsuba {passes}x{spp} spp, reference {ref['spp']} spp")
    print(f"{'block':>7} {'mitsuba (rgb mean)':>20} {'reference':>12} {'rel diff':>9} {'max |z|':>8}")
    for by in range(m.shape[0]):
        for bx in range(m.shape[1]):
            mm, rr = m[by, bx].mean(), r[by, bx].mean()
            print(f"{by:>3},{bx:<3} {mm:>20.5f} {rr:>12.5f} {100 * (rr - mm) / mm:>8.3f}% "
                  f"{np.abs(z[by, bx]).max():>8.2f}")
    rel_noise = np.max(se / m)
    print(f"max |rel diff| {100 * np.abs(rel).max():.3f}% (combined MC noise up to "
          f"{100 * rel_noise:.3f}%), mean rel diff {100 * rel.mean():+.3f}%, "
          f"max |z| {np.abs(z).max():.2f}, rms z {np.sqrt((z ** 2).mean()):.2f}")
    # The same against the cloud's own signal (how far a block is from the bare sky).
    dev = np.abs(m - np.array(setup["sky_radiance"]))
    cloudy = dev > 0.01 * m
    if cloudy.any():
        print(f"against the cloud's signal |block - sky| (blocks {cloudy.sum() // 3}): max "
              f"{100 * (np.abs(r - m)[cloudy] / dev[cloudy]).max():.2f}%, "
              f"total {100 * np.abs(r - m)[cloudy].sum() / dev[cloudy].sum():.2f}%")
    if name == "single":
        passed = np.abs(rel).max() < 0.01
        print(f"single scattering within 1% on every block and channel: {passed}")
    else:
        passed = np.abs(z).max() < 4.0
        print(f"all orders within the combined Monte Carlo noise (|z| < 4): {passed}")
    ok = ok and passed
sys.exit(0 if ok else 1)
