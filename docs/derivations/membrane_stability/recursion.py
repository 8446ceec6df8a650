"""The quasi-steady recursion (README.md section 2): fluid inertia neglected, U = M F, F = -A X* - D U,
lambda an eigenvalue of M A, z = lambda dt, d = D M (the explicit damping's gain)."""
import numpy as np

def one_step(z, d=0.0):
    # state (X_n, U_n): X* = X_n + dt U_n; U_{n+1} = M F = -z/dt X* - d U_n; X_{n+1} = X_n + dt U_{n+1}
    # with V = dt U:  V' = -z (X + V) - d V,  X' = X + V'
    return np.array([[1 - z, -z - d], [-z, -z - d]])

for z in [0.1, 0.5, 2 / 3, 0.7, 1.0, 4 / 3]:
    ev = np.linalg.eigvals(one_step(z))
    roots = np.roots([1, 2 * z - 1, -z])
    print(f"z = {z:.3f}: eigenvalues {np.sort(ev.real)}, roots of mu^2 + (2z-1) mu - z: {np.sort(roots.real)}")

# threshold by bisection on the spectral radius, and the slope d mu/dz at z = 2/3
rad = lambda z, d=0.0: max(abs(np.linalg.eigvals(one_step(z, d))))
lo, hi = 0.1, 2.0
for _ in range(60):
    m = 0.5 * (lo + hi)
    (lo, hi) = (m, hi) if rad(m) <= 1 else (lo, m)
print(f"threshold z = {lo:.6f} (2/3 = {2/3:.6f})")
e = 1e-6
print(f"d mu/dz at z = 2/3: {(min(np.linalg.eigvals(one_step(2/3 + e)).real) + 1) / e:.4f} (-9/5)")
for f in [1.05, 1.1, 1.25, 1.5, 2.0]:
    print(f"  z = {f:.2f} x 2/3: eigenvalue {min(np.linalg.eigvals(one_step(f * 2 / 3)).real):.3f}")
# with the explicit damping d = D M: threshold 3/2 z + d = 1
for d in [0.0, 0.142, 0.5, 0.9, 1.1]:
    lo, hi = 0.0, 3.0
    if rad(1e-9, d) > 1:
        print(f"d = {d}: unstable at any dt (d > 1)")
        continue
    for _ in range(60):
        m = 0.5 * (lo + hi)
        (lo, hi) = (m, hi) if rad(m, d) <= 1 else (lo, m)
    print(f"d = {d}: threshold z = {lo:.5f}, (1 - d)/1.5 = {(1 - d) / 1.5:.5f}")
# below the threshold the spurious root is about -z: the decay per step of a flipping mode
for z in [0.05, 0.1, 0.2, 0.4]:
    print(f"z = {z}: roots {np.sort(np.roots([1, 2 * z - 1, -z]).real)}")
