# Writes box_points_3d.xyz: the points of examples/deform_triangulation_3.cpp,
# the 5 x 5 x 5 lattice points on the surface of the unit cube [0,1]^3 (98)
# and 100 interior points of the Halton sequence (bases 2, 3, 5) shrunk to
# [0.1,0.9]^3. Run from this directory: /usr/bin/python3 box_points_3d.py
def halton(i, b):
    f, r = 1.0, 0.0
    while i > 0:
        f /= b
        r += f * (i % b)
        i //= b
    return r

with open("box_points_3d.xyz", "w") as out:
    for i in range(5):
        for j in range(5):
            for k in range(5):
                if 0 in (i, j, k) or 4 in (i, j, k):
                    out.write(f"{i / 4:g} {j / 4:g} {k / 4:g}\n")
    for n in range(1, 101):
        out.write(" ".join(f"{0.1 + 0.8 * halton(n, b):.6f}" for b in (2, 3, 5)) + "\n")
