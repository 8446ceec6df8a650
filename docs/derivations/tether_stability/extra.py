import numpy as np
from g1 import G1, thr
k=2.5;e=2.5e-7
for nA in [31.25,62.5,125]:
    f=lambda d:(e+k*d/2)*G1(0.2,12,1.0,nA,1.0,d)
    print("nA",nA,"both thr ns", thr(f,1e-9,5e-6)*1e9, " eta-only", thr(lambda d:e*G1(0.2,12,1.0,nA,1.0,d),1e-9,5e-6)*1e9)
# sheet at a node (Y=1.1um) vs midway: sensitivity
print("Y=1.1:",thr(lambda d:(e+k*d/2)*G1(0.2,12,1.1,62.5,1.0,d),1e-9,5e-6)*1e9)
print("Y=1.05:",thr(lambda d:(e+k*d/2)*G1(0.2,12,1.05,62.5,1.0,d),1e-9,5e-6)*1e9)
# per-point inertial mass vs single point
h=0.2e-4; ell=2.17*h; nA=62.5e8
print("sheet mass/pt",ell/nA," single-pt kernel mass",ell**3, "ratio",ell**3/(ell/nA), "n_A ell^2", nA*ell**2)
for r in [1.0,1.5]:
    M=1/(6*np.pi*0.01*r*h); print("single pt r_eff=%gh"%r, "M=%.3g eta*M=%.3g"%(M,e*M), "sheet/single", 5.366e7/M)
print("wall shear stress disp: k nA for s=0.5 800ns 1cP ~1e8 ->", 10/1e8*1e4, "um; seed:", 10/(2.5*6.25e9)*1e4,"um")
