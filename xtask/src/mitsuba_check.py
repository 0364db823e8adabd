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


def sky():
    # Under the physical sky, the map `export-volume` wrote (Mitsuba's lat-long convention, which
    # the reference's `Environment` follows), else the uniform ambient.
    if setup.get("sky_map"):
        return {"type": "envmap", "filename": setup["sky_map"]}
    return {"type": "constant", "radiance": {"type": "rgb", "value": setup["sky_radiance"]}}


def scene(integrator, box=True):
    return mi.load_dict({
        "type": "scene",
        "integrator": integrator,
        "sensor": {
            "type": "perspective",
            "fov": setup["fov_y_deg"],
            "fov_axis": "y",
            # Mitsuba's default far clip is 10 km: a box beyond it was invisible.
            "far_clip": 1e8,
            "to_world": T().look_at(origin=origin.tolist(), target=(origin + forward).tolist(),
                                    up=up.tolist()),
            "film": {"type": "hdrfilm", "width": w, "height": h, "pixel_format": "rgb",
                     "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        # Mitsuba's direction is the one light travels: away from the sun.
        "sun": {"type": "directional", "direction": [-c for c in setup["sun_direction"]],
                "irradiance": {"type": "rgb", "value": setup["sun_illuminance"]}},
        "sky": sky(),
        **({"box": box_shape()} if box else {}),
    })


def box_shape():
    return {
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
        }


# Mitsuba's image x runs along cross(forward, up) (look_at's "left" negated); the reference's
# along camera_right.
flip = np.dot(np.cross(forward, up), setup["camera_right"]) < 0


def mitsuba_passes(integrator):
    # Each pass's blocks.
    s = scene(integrator)
    per_pass = []
    for k in range(passes):
        img = np.array(mi.render(s, seed=1000 + k, spp=spp), dtype=np.float64)[:, :, :3]
        if flip:
            img = img[:, ::-1, :]
        per_pass.append(blocks(img))
    return np.array(per_pass)


def background():
    # What the camera sees with no box: the sky behind each pixel, averaged over the pixel as
    # Mitsuba's box filter does (the reference renders the medium's light and transmittance
    # alone; the sky it sees through is this, times the transmittance), and each pass's blocks.
    # The seeds are the renders' own, so that each pass's camera rays fall where theirs do and
    # the pixel's jitter over the sky's gradient cancels where the camera sees the sky (with
    # other seeds, `sunset`'s horizon below its cloud measured |z| 4.9 where no cloud is).
    s = scene({"type": "path", "max_depth": 1}, box=False)
    imgs = []
    for k in range(passes):
        img = np.array(mi.render(s, seed=1000 + k, spp=spp), dtype=np.float64)[:, :, :3]
        imgs.append(img[:, ::-1, :] if flip else img)
    imgs = np.array(imgs)
    return imgs.mean(axis=0), np.array([blocks(i) for i in imgs])


def map_lookup(env, d):
    # The convention `Environment` (crates/reference/src/environment.rs) states, in numpy:
    # u = atan2(x, -z) / 2pi, v = acos(y) / pi, columns centred on u = (i + 0.5) / width
    # (wrapping around), rows on v = j / (height - 1), bilinear between them.
    hh, ww = env.shape[:2]
    u = np.arctan2(d[..., 0], -d[..., 2]) / (2 * np.pi)
    u -= np.floor(u)
    v = np.arccos(np.clip(d[..., 1], -1, 1)) / np.pi
    x, y = u * ww - 0.5, v * (hh - 1)
    i, j = np.floor(x).astype(int), np.minimum(np.floor(y).astype(int), hh - 2)
    wx, wy = (x - i)[..., None], (y - j)[..., None]
    i0, i1 = i % ww, (i + 1) % ww
    top = env[j, i0] * (1 - wx) + env[j, i1] * wx
    bottom = env[j + 1, i0] * (1 - wx) + env[j + 1, i1] * wx
    return top * (1 - wy) + bottom * wy


def check_map_convention(bg):
    # Mitsuba reads the map as the reference does, in two ways, per block:
    # - the background Mitsuba renders against the map file looked up by the stated convention
    #   at Mitsuba's own pixel directions (8x8 a pixel, before the flip): Mitsuba's reading of
    #   the convention. A mirrored or shifted lookup differs by the sky's own gradients, which
    #   are steepest in the sun's glow at the horizon: on `sunset` columns on u = i / width
    #   instead of their centres differ by 2% a block;
    # - the same against the reference's own background, its lookup on the map in its memory:
    #   a file written flipped or transposed would pass the first and fail this one.
    env = np.array(mi.Bitmap(setup["sky_map"]), dtype=np.float64)[:, :, :3]
    tan = np.tan(np.radians(setup["fov_y_deg"]) / 2)
    # Mitsuba's image x (before the flip) runs along cross(forward, up).
    image_x = np.cross(forward, up)
    image_x /= np.linalg.norm(image_x)
    image_y = np.cross(image_x, forward)
    k = 8
    xs = (2 * (np.arange(w * k) + 0.5) / (w * k) - 1) * tan * w / h
    ys = (1 - 2 * (np.arange(h * k) + 0.5) / (h * k)) * tan
    d = forward + xs[None, :, None] * image_x + ys[:, None, None] * image_y
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    want = map_lookup(env, d).reshape(h, k, w, k, 3).mean(axis=(1, 3))
    got = bg[:, ::-1, :] if flip else bg
    rel = np.abs(blocks(got) - blocks(want)) / blocks(want)
    own = np.array(ref["background"], dtype=np.float64).reshape(h, w, 3)
    rel_own = np.abs(blocks(bg) - blocks(own)) / blocks(own)
    passed = rel.max() < 0.005 and rel_own.max() < 0.005
    print(f"the sky map as Mitsuba reads it: against its stated convention, max block "
          f"difference {100 * rel.max():.3f}%; against the reference's own lookup "
          f"{100 * rel_own.max():.3f}% (both within 0.5%: {passed})")
    return passed


def blocks(img):
    nby, nbx = h // block, w // block
    return img[: nby * block, : nbx * block].reshape(nby, block, nbx, block, 3).mean(axis=(1, 3))


def reference_blocks(name, sky):
    # The reference's blocks, with the sky it sees through the medium, their standard error
    # and their mean transmittance.
    r = np.array(ref[name]["radiance"], dtype=np.float64).reshape(h, w, 4)
    se = np.array(ref[name]["std_error"], dtype=np.float64).reshape(h, w, 4)
    n = block * block
    nby, nbx = h // block, w // block
    alpha = blocks(np.repeat(r[:, :, 3:4], 3, axis=2))
    if ref.get("background_included", False):
        # Under the physical sky the reference's pixels hold the sky seen through the medium
        # already (its own map, sub-pixel by sub-pixel, so that the sky's gradient and the
        # cloud's edges vary together within a pixel); where the camera sees the sky, Mitsuba's
        # own view of the map takes the place of the reference's (the two filters differ by up
        # to 0.07% a block), weighted by the transmittance.
        own = np.array(ref["background"], dtype=np.float64).reshape(h, w, 3)
        total = r[:, :, :3] + r[:, :, 3:4] * (sky - own)
        var = se[:, :, :3] ** 2
    else:
        # The reference's radiance is the in-scattered light; the camera also sees the uniform
        # sky through the medium (transmittance in alpha).
        total = r[:, :, :3] + r[:, :, 3:4] * sky
        var = se[:, :, :3] ** 2 + (se[:, :, 3:4] * sky) ** 2
    v = var[: nby * block, : nbx * block].reshape(nby, block, nbx, block, 3).sum(axis=(1, 3))
    return blocks(total), np.sqrt(v) / n, alpha


bg, bg_passes = background()
ok = check_map_convention(bg) if setup.get("sky_map") else True
for name, label, integrator in [
    ("single", "single scattering (volpath, max_depth=2)", {"type": "volpath", "max_depth": 2}),
    ("all", "all orders (volpathmis, max_depth=-1)", {"type": "volpathmis", "max_depth": -1}),
]:
    m_passes = mitsuba_passes(integrator)
    m = m_passes.mean(axis=0)
    r, r_se, alpha = reference_blocks(name, bg)
    # Mitsuba's part of the difference is its render less the sky the reference takes from it
    # (alpha times the background, whose jitter is the render's own pass by pass): its
    # standard error over the passes.
    d = m_passes - alpha[None] * bg_passes
    m_se = d.std(axis=0, ddof=1) / np.sqrt(passes)
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
    dev = np.abs(m - blocks(bg))
    cloudy = dev > 0.01 * m
    if cloudy.any():
        print(f"against the cloud's signal |block - sky| (blocks {cloudy.sum() // 3}): max "
              f"{100 * (np.abs(r - m)[cloudy] / dev[cloudy]).max():.2f}%, "
              f"total {100 * np.abs(r - m)[cloudy].sum() / dev[cloudy].sum():.2f}%")
    else:
        # A box that hardly changes the image compares the sky with itself.
        print("no block differs from the bare sky by 1%: the cloud is too thin or out of view "
              "to compare anything (move the box with --distance-m)")
        ok = False
    if name == "single":
        passed = np.abs(rel).max() < 0.01
        print(f"single scattering within 1% on every block and channel: {passed}")
    else:
        passed = np.abs(z).max() < 4.0
        print(f"all orders within the combined Monte Carlo noise (|z| < 4): {passed}")
    ok = ok and passed
sys.exit(0 if ok else 1)
