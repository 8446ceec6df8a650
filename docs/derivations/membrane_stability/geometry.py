"""Reference areas, data-site spacings and largest curvatures of the seed's cells (CGS printed in um)."""
import numpy as np

def surface(X, nt=1201, nl=1201):
    t = np.linspace(-np.pi / 2, np.pi / 2, nt)
    l = np.linspace(-np.pi, np.pi, nl)
    T, L = np.meshgrid(t, l, indexing="ij")
    x = X(L, T)
    xt = np.gradient(x, t, axis=1)
    xl = np.gradient(x, l, axis=2)
    n = np.cross(xl, xt, axis=0)
    dA = np.linalg.norm(n, axis=0)
    return np.trapz(np.trapz(dA, l, axis=1), t)

R0 = 3.91  # um
def rbc(l, t):
    ct, st = np.cos(t), np.sin(t)
    r = ct * ct
    return np.array([R0 * np.cos(l) * ct, R0 * np.sin(l) * ct, R0 * (0.105 + r - 0.56 * r * r) * st])
def plt(l, t):
    return np.array([1.55 * np.cos(l) * np.cos(t), 1.55 * np.sin(l) * np.cos(t), 0.5 * np.sin(t)])

def meridian_curvature(X, nt=20001):
    t = np.linspace(-np.pi / 2 + 1e-3, np.pi / 2 - 1e-3, nt)
    x = X(np.zeros_like(t), t)
    r, z = x[0], x[2]
    r1, z1 = np.gradient(r, t), np.gradient(z, t)
    r2, z2 = np.gradient(r1, t), np.gradient(z1, t)
    c = np.abs(r1 * z2 - z1 * r2) / (r1**2 + z1**2) ** 1.5
    return c.max()

A_rbc, A_plt = surface(rbc), surface(plt)
print(f"red cell area {A_rbc:.1f} um^2, largest meridional curvature {meridian_curvature(rbc):.2f} 1/um")
print(f"platelet area {A_plt:.2f} um^2, largest meridional curvature {meridian_curvature(plt):.2f} 1/um (a/c^2 = {1.55/0.25:.2f})")
for name, A, nd in [("red cell", A_rbc, 2500), ("red cell", A_rbc, 625), ("red cell", A_rbc, 400),
                    ("platelet", A_plt, 900), ("platelet", A_plt, 400)]:
    d = np.sqrt(A / nd)
    print(f"{name:9s} n_d = {nd:5d}: spacing {d:.3f} um, k_max = sqrt(4 pi)/spacing = {np.sqrt(4*np.pi)/d:.2f} 1/um")
