#!/usr/bin/env python3
"""Makes a segmented image (a binary mask: a blob with two holes) and turns it into a signed
distance grid that meshctl meshes (--sdf-grid). Python 3 and NumPy only.

    make_sdf.py blob.npy [--mask blob.pgm] [--width 160] [--height 120] [--spacing 0.01]
    meshctl generate --sdf-grid blob.npy --sdf-grid-spacing 0.01 --h0 0.025 -o blob.svg

The array is indexed [row j, column i], row 0 at the bottom (y = origin.y + j * dy), as meshctl
reads it; an image's rows run downwards, so flip an image with np.flipud before its transform.

The distance transform is exact for the mask's pixel centres: inside pixels get minus the
distance to the nearest outside pixel, outside pixels the distance to the nearest inside pixel,
each less half a pixel, so that the zero level runs between the two. The nearest pixel of the
other kind is always on that kind's border (a pixel with all four neighbours alike has one of
them nearer), so a brute force over border pixels is enough for a small image.

Two things matter for a good mesh. The values must be in the same length unit as the spacing
(pixels times --spacing): DistMesh's tolerances assume a distance, whose gradient is 1. And the
zero level of a mask's distance zigzags along the pixel staircase; edges several pixels long
cannot follow it, and the worst elements suffer (slivers in the notches). A few passes of a 3 x 3
box filter (--smooth) round the staircase off and leave the distance elsewhere nearly as it was
(a box filter keeps a linear function).
"""

import argparse
import sys

import numpy as np


def blob_mask(width, height):
    """True inside: where a sum of three Gaussians exceeds a threshold, minus two disks."""
    y, x = np.mgrid[0:height, 0:width].astype(float)
    x, y = x / width, y / height * height / width  # unit pixels, aspect kept
    f = np.zeros_like(x)
    for cx, cy, s in ((0.3, 0.35, 0.15), (0.65, 0.4, 0.17), (0.5, 0.55, 0.12)):
        f += np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * s * s))
    mask = f > 0.6
    for cx, cy, r in ((0.3, 0.35, 0.07), (0.68, 0.42, 0.09)):
        mask &= (x - cx) ** 2 + (y - cy) ** 2 > r * r
    return mask


def border(mask):
    """Pixels of `mask` with a 4-neighbour outside it (pixels beyond the image count as not in
    it), as an array of (row, column)."""
    padded = np.pad(mask, 1, constant_values=False)
    inner = (padded[1:-1, 1:-1] & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2]
             & padded[1:-1, 2:])
    return np.argwhere(mask & ~inner).astype(float)


def nearest_distance(points, targets, chunk=4096):
    """For each of `points` (#P by 2), the distance to the nearest of `targets` (#T by 2)."""
    out = np.empty(len(points))
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk, None, :]
        out[start:start + chunk] = np.sqrt(((p - targets[None, :, :]) ** 2).sum(-1)).min(1)
    return out


def signed_distance(mask):
    """Signed distance in pixels, negative inside `mask`, zero halfway between pixel centres."""
    sdf = np.empty(mask.shape)
    for inside, sign in ((True, -1.0), (False, 1.0)):
        here = mask == inside
        others = border(~here)
        if len(others) == 0:
            sys.exit("the mask is all inside or all outside: nothing to mesh")
        sdf[here] = sign * (nearest_distance(np.argwhere(here).astype(float), others) - 0.5)
    return sdf


def smooth(sdf, passes):
    """`passes` rounds of a 3 x 3 box filter, the border samples repeated outwards."""
    for _ in range(passes):
        p = np.pad(sdf, 1, mode="edge")
        rows, cols = sdf.shape
        sdf = sum(p[1 + dj:1 + dj + rows, 1 + di:1 + di + cols]
                  for dj in (-1, 0, 1) for di in (-1, 0, 1)) / 9.0
    return sdf


def write_pgm(path, mask):
    """The mask as a binary PGM, white inside, top row first as image viewers show it."""
    image = np.flipud(np.where(mask, 255, 0).astype(np.uint8))
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (mask.shape[1], mask.shape[0]))
        f.write(image.tobytes())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", help="the signed-distance grid, a .npy file (float32)")
    parser.add_argument("--mask", help="also write the segmented image as a .pgm")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=120)
    parser.add_argument("--spacing", type=float, default=0.01,
                        help="the length of a pixel (meshctl's --sdf-grid-spacing)")
    parser.add_argument("--smooth", type=int, default=2, help="3 x 3 box filter passes")
    args = parser.parse_args()
    mask = blob_mask(args.width, args.height)
    sdf = args.spacing * smooth(signed_distance(mask), args.smooth)
    np.save(args.output, sdf.astype(np.float32))
    if args.mask:
        write_pgm(args.mask, mask)
    print(f"{args.output}: {args.height} x {args.width} samples, {mask.sum()} pixels inside")


if __name__ == "__main__":
    main()
