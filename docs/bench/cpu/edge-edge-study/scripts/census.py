import json, numpy as np, sys
C=R=40; sp=1.2/39; h=0.02
def edges():
    E=[]
    for r in range(R):
        for c in range(C):
            a=c+r*C
            if c+1<C: E.append((a,a+1))
            if r+1<R: E.append((a,a+C))
            if c+1<C and r+1<R: E.append((a+1,a+C))
    return np.array(E)
E=edges()
def segnear(P1,Q1,P2,Q2):
    d1=Q1-P1; d2=Q2-P2; r=P1-P2
    a=(d1*d1).sum(-1); e=(d2*d2).sum(-1); f=(d2*r).sum(-1); c=(d1*r).sum(-1); b=(d1*d2).sum(-1)
    den=a*e-b*b
    s=np.where(den>1e-5*a*e, np.clip((b*f-c*e)/np.where(den>0,den,1),0,1),0.0)
    t=(b*s+f)/e
    lo=t<0; hi=t>1
    s=np.where(lo,np.clip(-c/a,0,1),np.where(hi,np.clip((b-c)/a,0,1),s)); t=np.clip(t,0,1)
    off=(P1+s[...,None]*d1)-(P2+t[...,None]*d2)
    return np.linalg.norm(off,axis=-1),s,t
rest=np.array([[ (k%C)*sp,(k//C)*sp,0.0] for k in range(C*R)])
for fn in sys.argv[1:]:
    x=np.array(json.load(open(fn))['objects'][0]['positions'])
    per=np.zeros(C*R,int); per_int=np.zeros(C*R,int)
    for i in range(len(E)):
        e1=E[i]; e2=E[i+1:]
        share=(e2[:,0]==e1[0])|(e2[:,0]==e1[1])|(e2[:,1]==e1[0])|(e2[:,1]==e1[1])
        d,s,t=segnear(x[e1[0]][None],x[e1[1]][None],x[e2[:,0]],x[e2[:,1]])
        dr,_,_=segnear(rest[e1[0]][None],rest[e1[1]][None],rest[e2[:,0]],rest[e2[:,1]])
        keep=(~share)&(dr>=1.5*h)&(d<2*h)
        idx=np.nonzero(keep)[0]
        for k in idx:
            a,b=e1; j,l=e2[k]
            # owner: lower index of the nearest pair of ends
            best=None
            for u in (a,b):
                for w in (j,l):
                    dd=np.sum((x[u]-x[w])**2)
                    key=(dd,min(u,w),max(u,w))
                    if best is None or key<best[0]: best=(key,min(u,w))
            per[best[1]]+=1
            if min(s[k],1-s[k],t[k],1-t[k])>0.0: per_int[best[1]]+=1
    print(fn, 'EE within 2h: total',per.sum(),'max/particle',per.max(),'particles >32:',(per>32).sum(),'>128:',(per>128).sum(),'mean over nonzero %.1f'%per[per>0].mean(), '| interior-only max',per_int.max(),'total',per_int.sum())

def lineparams(P1,Q1,P2,Q2):
    d1=Q1-P1; d2=Q2-P2; r=P1-P2
    a=(d1*d1).sum(-1); e=(d2*d2).sum(-1); f=(d2*r).sum(-1); c=(d1*r).sum(-1); b=(d1*d2).sum(-1)
    den=a*e-b*b
    sin2=den/(a*e)
    s=(b*f-c*e)/np.where(den>0,den,1); t=(a*f-b*c)/np.where(den>0,den,1)
    return s,t,np.sqrt(np.maximum(sin2,0)),np.sqrt(a),np.sqrt(e)
print('--- filter study')
for fn in sys.argv[1:]:
    x=np.array(json.load(open(fn))['objects'][0]['positions'])
    tot=0; stats={}
    for reach in (2.0,1.5):
        for k_s in (None, 2.0, 1.0):
            stats[(reach,k_s)]=0
    for i in range(len(E)):
        e1=E[i]; e2=E[i+1:]
        share=(e2[:,0]==e1[0])|(e2[:,0]==e1[1])|(e2[:,1]==e1[0])|(e2[:,1]==e1[1])
        d,_,_=segnear(x[e1[0]][None],x[e1[1]][None],x[e2[:,0]],x[e2[:,1]])
        dr,_,_=segnear(rest[e1[0]][None],rest[e1[1]][None],rest[e2[:,0]],rest[e2[:,1]])
        s,t,sn,L1,L2=lineparams(x[e1[0]][None],x[e1[1]][None],x[e2[:,0]],x[e2[:,1]])
        for reach in (2.0,1.5):
            delta=(reach-1.0)*h*0.49
            keep=(~share)&(dr>=1.5*h)&(d<reach*h)
            for k_s in (None,2.0,1.0):
                if k_s is None:
                    ok=keep
                else:
                    # foot shift bound (in length), per side, times safety k_s
                    lev1=np.abs(1-s)+np.abs(s); lev2=np.abs(1-t)+np.abs(t)
                    shift=k_s*delta*(lev1+lev2)/np.maximum(sn,1e-6)
                    ms=shift/L1; mt=shift/L2
                    inside=(s>-ms)&(s<1+ms)&(t>-mt)&(t<1+mt)
                    ok=keep&((sn<0.25)|inside)
                stats[(reach,k_s)]+=ok.sum()
    print(fn, {f'{k[0]}h,k={k[1]}':v for k,v in stats.items()})
