import numpy as np
from g1 import G1
rho=1.0
def approx(h_um,nA_um2,mu_cP,dt,c,Heff_um):
    h=h_um*1e-4; mu=mu_cP*1e-2; nA=nA_um2*1e8; nu=mu/rho; ell=2.17*h
    return nA/(2*rho*np.sqrt(ell**2+c*nu*dt)/dt + mu/(Heff_um*1e-4))
cases=[(h,nA,mu,dt) for (h,nA) in [(0.2,62.5),(0.4,16.0)] for mu in [1.0,0.1] for dt in [25e-9,50e-9,100e-9,200e-9,400e-9,800e-9,1.6e-6,1e-5]]
ex=np.array([G1(h,12,1.0,nA,mu,dt) for (h,nA,mu,dt) in cases])
best=None
for c in np.linspace(1,12,45):
  for He in [0.8,0.83,0.86,0.9,0.95,1.0]:
    r=np.array([approx(h,nA,mu,dt,c,He) for (h,nA,mu,dt) in cases])/ex
    e=np.max(np.abs(np.log(r)))
    if best is None or e<best[0]: best=(e,c,He,r)
print(best[:3]); print(np.round(best[3],3))
for c in [4,5,6,8]:
    r=np.array([approx(h,nA,mu,dt,c,0.86) for (h,nA,mu,dt) in cases])/ex; print(c,np.round(r,2))
