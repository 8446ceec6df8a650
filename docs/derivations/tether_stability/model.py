import numpy as np
def b3(r):
    r=abs(r)
    return np.where(r<1,2/3-r**2+r**3/2,np.where(r<2,(2-r)**3/6,0.0))
def stepmat(h_um,L_um,Y_um,nA_um2,mu_cP,dt,k,eta,predicted=False,rho=1.0,steady=False):
    # CGS
    h=h_um*1e-4; N=int(round(L_um/h_um)); Y=Y_um*1e-4; nA=nA_um2*1e8; mu=mu_cP*1e-2
    y=(np.arange(N)+0.5)*h
    w=b3((y-Y)/h)               # interpolation weights (1D; x,z weights sum to 1 for uniform mode)
    J=w[None,:]                  # U = J u
    S=(nA*w/h)[:,None]           # f = S F  (dyn/cm^3 per dyn/point)
    Lap=(np.diag(-2*np.ones(N))+np.diag(np.ones(N-1),1)+np.diag(np.ones(N-1),-1))
    Lap[0,0]=-3; Lap[-1,-1]=-3; Lap/=h*h   # Dirichlet walls on cell faces (ghost = -u)
    a=0 if steady else rho/dt
    A=np.linalg.inv(a*np.eye(N)-mu*Lap)
    etae=eta+(k*dt if predicted else 0)
    # state z=[u (N), x (1)]
    Mu_u=A@(a*np.eye(N)-etae*S@J)
    Mu_x=A@(-k*S)
    M=np.zeros((N+1,N+1))
    M[:N,:N]=Mu_u; M[:N,N:]=Mu_x
    M[N:,:N]=dt*J@Mu_u; M[N:,N:]=1+dt*J@Mu_x
    return M
def rad(*a,**kw):
    return max(abs(np.linalg.eigvals(stepmat(*a,**kw))))
if __name__=="__main__":
    k=2.5;eta=2.5e-7
    for (h,nA) in [(0.2,62.5),(0.4,16.0)]:
      for mu in [1.0,0.1]:
        print(f"h={h} nA={nA} mu={mu}cP")
        for dt in [12.5e-9,25e-9,50e-9,100e-9,200e-9,400e-9,800e-9]:
            r_both=rad(h,12,1.0,nA,mu,dt,k,eta); r_k=rad(h,12,1.0,nA,mu,dt,k,0); r_e=rad(h,12,1.0,nA,mu,dt,0,eta)
            r_p=rad(h,12,1.0,nA,mu,dt,k,eta,predicted=True)
            print(f"  dt={dt*1e9:5.1f}ns  both {r_both:.3f}  k-only {r_k:.3f}  eta-only {r_e:.3f}  both@X* {r_p:.3f}")
