import numpy as np, itertools
N=15; s=1.0; h=0.65
def segd(p1,q1,p2,q2):
    # brute sample distance (2D in-plane), fine resolution
    t=np.linspace(0,1,41)
    A=p1[None,:]+t[:,None]*(q1-p1)[None,:]; B=p2[None,:]+t[:,None]*(q2-p2)[None,:]
    return np.min(np.linalg.norm(A[:,None,:]-B[None,:,:],axis=2))
edges=[]
for r in range(N):
    for c in range(N):
        if c+1<N: edges.append(((c,r),(c+1,r)))
        if r+1<N: edges.append(((c,r),(c,r+1)))
        if c+1<N and r+1<N: edges.append(((c+1,r),(c,r+1)))  # diagonal of the cell as triangles (a+1, a+cols)
mid=[e for e in edges if all(5<=v[0]<=9 and 5<=v[1]<=9 for v in e)]
cnt={'in2h':0,'in1.5':0}
for e1 in mid:
    for e2 in edges:
        if e1==e2 or set(e1)&set(e2): continue
        d=segd(np.array(e1[0],float),np.array(e1[1],float),np.array(e2[0],float),np.array(e2[1],float))
        if d<1.5*h: continue
        if d<2*h: cnt['in2h']+=1
print(len(mid), cnt, 'pairs per vertex ~', cnt['in2h']/len(mid)*3/2)
