"""A continuum estimate of the triangle count of lekalo's mesh of the benchmark surface (the
bicubic 50x50-patch surface of occt_mesh_deviation.py) at tolerance 1e-4 under two deviation
bounds for a rectangle of steps (h_u, h_v) split into two triangles by a diagonal:

  any-triangle: (A h_u^2 + 2 B h_u h_v + C h_v^2) / 8   (docs/theory/queries.md#tessellation;
            lekalo's rule for rational surfaces)
  edges:    (1/2) rho^2, rho the radius of the smallest disc around a triangle whose squared
            sides are M_a, M_b, M_c = max |D^2 S[e, e]| for the triangle's edge vectors e:
            A h_u^2, C h_v^2 and |S_uu h_u^2 +- 2 S_uv h_u h_v + S_vv h_v^2| along the diagonal,
            which is taken, point by point, as the one with the smaller bound (or fixed);
            lekalo's rule for polynomial surfaces.

The second bound follows from interpolating along the segment through a point parallel to one
edge and then along the other two edges: |S - L| <= (1/2)(l0 l1 M_a + l0 l2 M_b + l1 l2 M_c);
its maximum over the triangle is the circumradius formula M_a M_b M_c / (2(M_a M_b + M_b M_c +
M_c M_a) - M_a^2 - M_b^2 - M_c^2) where each M is below the sum of the other two, otherwise
max(M) / 4. The second derivatives are taken pointwise on a 120 x 120 grid and each point gets
the cell of the best aspect ratio (triangles per area 2 / (h_u h_v) at the tolerance): an
estimate of how far a bound can take the count, without the parts' nets, the dyadic lattice or
the strips that join parts of different sizes (lekalo's real count is 1.49x this estimate with
the any-triangle bound, 1,059,868, and 1.64x with the edge bound, 468,416 after its vertex
removal). It also checks the bound on 300 random small triangles of the surface:
the deviation on a barycentric grid of step 1/30 against the bound from the largest
|D^2 S[e, e]| on that grid.

    python bench/peers/mesh_bound_estimate.py      (needs numpy and OCP, as occt_mesh_deviation.py)
"""
import numpy as np

from occt_mesh_deviation import Surface, fine_grid

TOL = 1e-4


def disc_bound(ma, mb, mc):
    """max over the triangle of (1/2)(l0 l1 ma + l0 l2 mb + l1 l2 mc), elementwise."""
    denom = 2 * (ma * mb + mb * mc + mc * ma) - ma**2 - mb**2 - mc**2
    acute = (ma < mb + mc) & (mb < mc + ma) & (mc < ma + mb) & (denom > 0)
    inner = np.where(acute, ma * mb * mc / np.where(acute, denom, 1.0), 0.0)
    return 0.5 * np.maximum(inner, np.maximum(ma, np.maximum(mb, mc)) / 4)


def main():
    g = np.linspace(0.005, 0.995, 120)
    u, v = np.meshgrid(g, g, indexing="ij")
    _, _, _, suu, suv, svv = Surface().eval(np.stack([u.ravel(), v.ravel()], axis=1), True)
    norm = lambda x: np.linalg.norm(x, axis=-1)
    a, b, c = norm(suu), norm(suv), norm(svv)
    ratios = np.exp(np.linspace(np.log(0.05), np.log(20.0), 161))  # h_v / h_u, with h_u = 1
    best = {"any-triangle": 0.0, "edges, diagonal fixed": 0.0, "edges, better diagonal": 0.0}
    for r in ratios:
        any_triangle = (a + 2 * b * r + c * r * r) / 8
        diag = [disc_bound(a, c * r * r, norm(suu + 2 * s * suv * r + svv * r * r))
                for s in (1, -1)]
        # cell area at the tolerance for this aspect: h_u^2 r with h_u^2 = TOL / bound(h_u = 1)
        for name, bound in (("any-triangle", any_triangle), ("edges, diagonal fixed", diag[0]),
                            ("edges, better diagonal", np.minimum(*diag))):
            best[name] = np.maximum(best[name], TOL * r / bound)
    counts = {name: 2 * np.mean(1 / area) for name, area in best.items()}
    for name, n in counts.items():
        print(f"{name}: {n:,.0f} triangles ({n / counts['any-triangle']:.2f}x the any-triangle "
              "bound's)")

    surf, grid, rng, worst = Surface(), fine_grid(30), np.random.default_rng(3), 0.0
    for _ in range(300):
        corners = np.clip(0.05 + 0.9 * rng.random(2)
                          + (0.002 + 0.03 * rng.random()) * rng.standard_normal((3, 2)), 0, 1)
        x = grid @ corners
        dev = norm(surf.eval(x) - grid @ surf.eval(corners)).max()
        d = surf.eval(np.vstack([x, corners]), True)
        m = [norm(d[3] * e[0] ** 2 + 2 * d[4] * e[0] * e[1] + d[5] * e[1] ** 2).max()
             for e in (corners[1] - corners[0], corners[2] - corners[0], corners[2] - corners[1])]
        worst = max(worst, dev / disc_bound(*map(np.array, m)))
    print(f"300 random triangles: largest deviation / edge bound {worst:.3f}")


if __name__ == "__main__":
    main()
