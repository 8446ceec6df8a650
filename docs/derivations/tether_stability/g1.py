import numpy as np
from model import b3, stepmat
def G1(h_um,L_um,Y_um,nA_um2,mu_cP,dt,rho=1.0,factor=2.0):
    h=h_um*1e-4; N=int(round(L_um/h_um)); Y=Y_um*1e-4; nA=nA_um2*1e8; mu=mu_cP*1e-2
    y=(np.arange(N)+0.5)*h; w=b3((y-Y)/h)
    Lap=(np.diag(-2*np.ones(N))+np.diag(np.ones(N-1),1)+np.diag(np.ones(N-1),-1)); Lap[0,0]=-3; Lap[-1,-1]=-3; Lap/=h*h
    a=factor*rho/dt if dt else 0.0
    return nA*w@np.linalg.solve(a*np.eye(N)-mu*Lap,w/h)   # cm/s per dyn (per-point, collective sliding mode)
def thr(f,lo,hi):
    # largest x in [lo,hi] with f(x)<=1 (f increasing)
    for _ in range(60):
        m=np.sqrt(lo*hi)
        if f(m)>1+1e-9: hi=m
        else: lo=m
    return lo
def rad(*a,**kw): return max(abs(np.linalg.eigvals(stepmat(*a,**kw))))
k=2.5; eta=2.5e-7
for (h,nA) in [(0.2,62.5),(0.4,16.0)]:
  for mu in [1.0,0.1]:
    Ginf=G1(h,12,1.0,nA,mu,None)
    print(f"\nh={h} nA={nA}/um2 mu={mu} cP: quasi-steady G1 = {Ginf:.3e} cm/s/dyn -> eta*G1 = {eta*Ginf:.2f}, H_eff = {Ginf*mu*1e-2/(nA*1e8)*1e4:.3f} um; rho H^2/mu = {1*(1e-4)**2/(mu*1e-2)*1e9:.0f} ns")
    # thresholds: exact (spectral radius of full step) vs formula
    for lab,kk,ee,pred in [("k only",k,0,False),("eta only",0,eta,False),("both",k,eta,False),("both@X*",k,eta,True)]:
        dtx=thr(lambda d: rad(h,12,1.0,nA,mu,d,kk,ee,predicted=pred),1e-9,5e-6)
        e_eff=ee+(kk*1e0 and 0)
        fml=thr(lambda d: (ee+(1.5 if pred else 0.5)*kk*d)*G1(h,12,1.0,nA,mu,d),1e-9,5e-6)
        print(f"  {lab:9s}: exact dt_max = {dtx*1e9:7.1f} ns   formula (eta+c k dt) G1(dt) = 1: {fml*1e9:7.1f} ns")
