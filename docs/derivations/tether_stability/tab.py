import numpy as np
from g1 import G1, thr
from model import b3
k=2.5; eta=2.5e-7; rho=1.0
def approx(h_um,nA_um2,mu_cP,dt,H_um=1.0,L_um=12.0,ell_h=2.17):
    h=h_um*1e-4; mu=mu_cP*1e-2; nA=nA_um2*1e8; H=H_um*1e-4; L=L_um*1e-4
    kap=np.sqrt(2*rho/(mu*dt))
    G=np.sinh(kap*H)*np.sinh(kap*(L-H))/(kap*np.sinh(kap*L))  # point Green's fn (length)
    # series combination: kernel layer's inertia + the Brinkman/gap response
    return nA/(mu*kap**2*ell_h*h*0.5 + mu/G)   # test form
print("eta-only check at 0.1 cP, 50 ns, h=0.2: eta=3.75e-7 -> gain",3.75e-7*G1(0.2,12,1,62.5,0.1,50e-9), " eta=2.5e-7 ->",2.5e-7*G1(0.2,12,1,62.5,0.1,50e-9))
print("with k: (eta+k dt/2)G1 at 0.1cP 50ns:",(eta+k*50e-9/2)*G1(0.2,12,1,62.5,0.1,50e-9), "25ns:",(eta+k*25e-9/2)*G1(0.2,12,1,62.5,0.1,25e-9))
print("1 cP 50 ns:",(eta+k*50e-9/2)*G1(0.2,12,1,62.5,1.0,50e-9), " at X*:",(eta+1.5*k*50e-9)*G1(0.2,12,1,62.5,1.0,50e-9))
for mu in [1.0,0.1]:
  for (h,nA) in [(0.2,62.5),(0.4,16.0)]:
    print(f"\nmu={mu} cP h={h} nA={nA}")
    print(" dt(ns)  G1(cm/s/dyn)  G1*dt/(n_A dt/2rho l)  eta*G1  k dt/2*G1  (eta+k dt/2)G1  approx/exact  sqrt(nu dt/2)(um)")
    for dt in [25e-9,50e-9,100e-9,200e-9,400e-9,800e-9,1.6e-6,1e-5,1e-3]:
        g=G1(h,12,1.0,nA,mu,dt); nu=mu*1e-2/rho
        inert=nA*1e8*dt/(2*rho*2.17*h*1e-4)
        print(f" {dt*1e9:7.0f} {g:11.3e} {g/inert:8.3f} {eta*g:8.3f} {k*dt/2*g:8.3f} {(eta+k*dt/2)*g:8.3f} {approx(h,nA,mu,dt)/g:7.3f} {np.sqrt(nu*dt/2)*1e4:7.3f}")
