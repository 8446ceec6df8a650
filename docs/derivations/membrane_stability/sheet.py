"""The regularized mobility of a planar sheet's Fourier mode on the periodic MAC grid with the
B3 kernel (the model of README.md section 2). CGS units throughout.

    M_e(k; a) = Phi(kx h)^2 Phi(kz h)^2 (1/(N h)) sum_m <|w_m|^2> (1 - (e.d_m)^2/|d_m|^2) / (a + mu |d_m|^2)

the sheet in the plane y = y0 (averaged over y0 within a cell), the in-plane wavevector k = (kx, 0, kz),
e the polarization (n: normal y; L: along k; T: across k), d_m = (2/h) sin(k_m h/2) the MAC difference
symbols with ky_m = 2 pi m/(N h), w_m the discrete Fourier transform of the B3 weights across the sheet.
a = 0: the quasi-steady (Stokes) mobility M; a = 2 rho/dt: the mobility G(dt) of a mode that flips sign
every step (Brinkman/Helmholtz screening).
"""
import numpy as np

def phi_b3(r):
    a = np.abs(r)
    return np.where(a <= 1, 2 / 3 - a * a + 0.5 * a**3, np.where(a <= 2, (2 - a) ** 3 / 6, 0.0))

def Phi_b3(xi):
    """Fourier transform of B3 (unit spacing): (sin(xi/2)/(xi/2))^4."""
    x = np.asarray(xi, dtype=float) / 2
    return np.sinc(x / np.pi) ** 4

# the library's other kernels (lib/rbfib/ib/kernel_*.hpp), for the constants of README section 5
def _peskin4(r):
    a = np.abs(r)
    q = np.clip(-7 + 12 * a - 4 * a * a, 0, None)
    return np.where(a <= 1, (3 - 2 * a + np.sqrt(np.clip(1 + 4 * a - 4 * a * a, 0, None))) / 8,
                    np.where(a <= 2, (5 - 2 * a - np.sqrt(q)) / 8, 0.0))
def _roma3(r):
    a = np.abs(r)
    b = 1 - a
    return np.where(a <= 0.5, (1 + np.sqrt(np.clip(1 - 3 * a * a, 0, None))) / 3,
                    np.where(a <= 1.5, (5 - 3 * a - np.sqrt(np.clip(1 - 3 * b * b, 0, None))) / 6, 0.0))
def _cosine4(r):
    a = np.abs(r)
    return np.where(a <= 2, 0.25 * (1 + np.cos(np.pi / 2 * a)), 0.0)
KERNELS = {"bspline3": phi_b3, "peskin4": _peskin4, "roma3": _roma3, "cosine4": _cosine4}
_r = np.linspace(0, 2, 8001)
def Phi(xi, kernel="bspline3"):
    """The kernel's Fourier transform at xi (unit spacing)."""
    if kernel == "bspline3":
        return Phi_b3(xi)
    xi = np.asarray(xi, dtype=float)
    f = KERNELS[kernel](_r)
    return 2 * np.trapz(f * np.cos(np.multiply.outer(xi, _r)), _r, axis=-1)

_cache = {}
def wbar2(N, offsets=32, kernel="bspline3"):
    """<|sum_j phi(j - y0) exp(-2 pi i m j/N)|^2> over y0 in [0, 1), m = 0..N-1."""
    if (N, kernel) in _cache:
        return _cache[(N, kernel)]
    j = np.arange(N)
    acc = np.zeros(N)
    for s in (np.arange(offsets) + 0.5) / offsets:
        y0 = N // 2 + s
        w = KERNELS[kernel](j - y0)
        acc += np.abs(np.fft.fft(w)) ** 2
    _cache[(N, kernel)] = acc / offsets
    return _cache[(N, kernel)]

def mobility(k, h, mu, a=0.0, pol="L", angle=0.0, N=None, Ly=16e-4, kernel_in_plane=True, kernel="bspline3"):
    """k (1/cm) the Lagrangian in-plane wavenumber at `angle` (rad) to the grid's x axis.
    kernel_in_plane=False leaves out the factor Phi(kx h)^2 Phi(kz h)^2 (the grid part alone)."""
    if N is None:
        N = int(round(Ly / h))
    kx, kz = k * np.cos(angle), k * np.sin(angle)
    m = np.fft.fftfreq(N, d=1.0 / N)
    ky = 2 * np.pi * m / (N * h)
    dx, dz = 2 / h * np.sin(kx * h / 2), 2 / h * np.sin(kz * h / 2)
    dy = 2 / h * np.sin(ky * h / 2)
    d2 = dx**2 + dy**2 + dz**2
    if pol == "n":
        ed = dy
    elif pol == "L":
        ed = (np.cos(angle) * dx + np.sin(angle) * dz) * np.ones_like(dy)
    else:
        ed = (-np.sin(angle) * dx + np.cos(angle) * dz) * np.ones_like(dy)
    ok = d2 > 0
    P = np.zeros_like(d2)
    P[ok] = 1 - ed[ok] ** 2 / d2[ok]
    s = np.sum(wbar2(N, kernel=kernel)[ok] * P[ok] / (a + mu * d2[ok])) / (N * h)
    return (Phi(kx * h, kernel) ** 2 * Phi(kz * h, kernel) ** 2 if kernel_in_plane else 1.0) * s

if __name__ == "__main__":
    mu, h = 0.01, 0.2e-4
    print("continuum check (h = 0.2 um, 1 cP, Ly = 64 um): mobility x 4 mu k (n, L) and x 2 mu k (T)")
    print("  k (1/um)   n        L        T     |Phi(kh)|^2")
    for k_um in [0.5, 1, 2, 4, 6, 8, 12, 15.7]:
        k = k_um * 1e4
        Mn = mobility(k, h, mu, pol="n", Ly=64e-4) * 4 * mu * k
        ML = mobility(k, h, mu, pol="L", Ly=64e-4) * 4 * mu * k
        MT = mobility(k, h, mu, pol="T", Ly=64e-4) * 2 * mu * k
        print(f"  {k_um:6.2f}   {Mn:.4f}   {ML:.4f}   {MT:.4f}   {Phi_b3(k*h)**2:.4f}")
