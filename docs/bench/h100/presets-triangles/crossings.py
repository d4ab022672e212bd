# Crossing edges in a `simulate --out` state: each cloth edge (the renderer's two triangles a
# cell) through one of its own triangles that shares no vertex with it, and edges of each
# object through another cloth's triangles (exact segment-triangle tests). Usage:
# python3 crossings.py state.json
import json, sys, numpy as np
def tris(c, r):
    t=[]
    for j in range(r-1):
        for i in range(c-1):
            a=i+j*c
            t.append((a,a+c,a+1)); t.append((a+1,a+c,a+c+1))
    return np.array(t)
def edges(T):
    e=set()
    for a,b,c in T:
        for u,v in ((a,b),(b,c),(a,c)):
            e.add((min(u,v),max(u,v)))
    return np.array(sorted(e))
def count(P, E, T, P2=None, T2=None, same=True):
    # segments E in P through triangles T in P2
    if P2 is None: P2=P
    p=P[E[:,0]]; q=P[E[:,1]]
    a=P2[T[:,0]]; b=P2[T[:,1]]; c=P2[T[:,2]]
    n=0; crossed=set()
    lo=np.minimum(np.minimum(a,b),c); hi=np.maximum(np.maximum(a,b),c)
    for i in range(len(E)):
        slo=np.minimum(p[i],q[i]); shi=np.maximum(p[i],q[i])
        m=np.all(hi>=slo,axis=1)&np.all(lo<=shi,axis=1)
        if same:
            m&=~np.any(T==E[i,0],axis=1)&~np.any(T==E[i,1],axis=1)
        idx=np.nonzero(m)[0]
        if len(idx)==0: continue
        A=a[idx];B=b[idx];C=c[idx]
        nn=np.cross(B-A,C-A)
        dp=np.einsum('ij,ij->i',p[i]-A,nn); dq=np.einsum('ij,ij->i',q[i]-A,nn)
        s=(dp*dq<0)
        t=dp/(dp-dq+1e-300)
        X=p[i]+t[:,None]*(q[i]-p[i])
        def side(U,V):
            return np.einsum('ij,ij->i',np.cross(V-U,X-U),nn)
        inside=(side(A,B)>=0)&(side(B,C)>=0)&(side(C,A)>=0)
        if np.any(s&inside): n+=1
    return n
d=json.load(open(sys.argv[1]))
objs=[]
for o in d['objects']:
    P=np.array(o['positions'],dtype=float)
    if o['kind']=='cloth':
        c,r=o['dims']; T=tris(c,r); E=edges(T)
    else:
        T=None; E=np.array([(i,i+1) for i in range(len(P)-1)])
    objs.append((o['name'],P,E,T))
for na,P,E,T in objs:
    if T is not None: print(na,'self',count(P,E,T))
for na,P,E,T in objs:
    for nb,P2,E2,T2 in objs:
        if na!=nb and T2 is not None: print(na,'through',nb,count(P,E,T2,P2,T2,same=False))
