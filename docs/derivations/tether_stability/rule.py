import numpy as np
from g1 import G1
from model import stepmat
k0=2.5; e0=2.5e-7
def dom(h,nA,mu,dt,k,eta,pred=False):
    ev=np.linalg.eigvals(stepmat(h,12,1.0,nA,mu,dt,k,eta,predicted=pred)); i=np.argmax(abs(ev)); return ev[i]
for (h,nA) in [(0.2,62.5),(0.4,16.0)]:
  for mu in [1.0,0.1]:
    print(f"\n== h={h} um, n_A={nA}/um^2, mu={mu} cP")
    print(" dt(ns) G1(cm/s/dyn) 1/G1=eta_lim  k_lim=2/(dt G1)  seed gain | rule s=0.8: k, eta (|lam|)   | rule s=0.5: k, eta  | k n_A (dyn/cm^3), eta n_A (s=0.5)")
    for dt in [50e-9,100e-9,200e-9,400e-9,800e-9]:
        g=G1(h,12,1.0,nA,mu,dt); B=1/g
        out=[]
        for s in [0.8,0.5]:
            eta=0.8*s*B; k=0.4*s*B/dt
            lam=abs(dom(h,nA,mu,dt,k,eta)); out.append((k,eta,lam))
        print(f" {dt*1e9:5.0f} {g:10.3e} {B:10.3e} {2*B/dt:10.3e} {(e0+k0*dt/2)*g:7.3f} | {out[0][0]:.3g} {out[0][1]:.3g} ({out[0][2]:.4f}) | {out[1][0]:.3g} {out[1][1]:.3g} ({out[1][2]:.4f}) | {out[1][0]*nA*1e8:.3g} {out[1][1]*nA*1e8:.3g}")
print("\nsweep: dominant eigenvalue (seed constants), h=0.2 nA=62.5")
for mu in [1.0,0.1]:
  for lab,k,e,p in [("both",k0,e0,False),("k only",k0,0,False),("eta only",0,e0,False),("both@X*",k0,e0,True)]:
    s=[]
    for dt in [25,40,50,60,65,70,80,90,100,120,150]:
        l=dom(0.2,62.5,mu,dt*1e-9,k,e,p); s.append(f"{dt}:{l.real:+.3f}{'' if abs(l.imag)<1e-9 else 'c'}")
    print(f" mu={mu} {lab:9s}", " ".join(s))
print("\nsweep h=0.4 nA=16 mu=1:")
for lab,k,e,p in [("both",k0,e0,False),("both@X*",k0,e0,True)]:
    s=[]
    for dt in [100,150,200,250,280,300,400,800]:
        l=dom(0.4,16,1.0,dt*1e-9,k,e,p); s.append(f"{dt}:{l.real:+.3f}{'' if abs(l.imag)<1e-9 else 'c'}")
    print(f" {lab:9s}"," ".join(s))
