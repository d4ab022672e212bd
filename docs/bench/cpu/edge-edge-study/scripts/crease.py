import json, numpy as np, sys
exec(open('/tmp/census.py').read().split("rest=np.array")[0])
rest=np.array([[ (k%C)*sp,(k//C)*sp,0.0] for k in range(C*R)])
# opposite vertices
opp={}
for r in range(R-1):
    for c in range(C-1):
        a=c+r*C
        for tv in ((a,a+C,a+1),(a+1,a+C,a+C+1)):
            for k in range(3):
                u,w=tv[k],tv[(k+1)%3]; opp.setdefault((min(u,w),max(u,w)),[]).append(tv[(k+2)%3])
half=0.5*np.hypot(sp,sp)
for fn in sys.argv[1:]:
    x=np.array(json.load(open(fn))['objects'][0]['positions'])
    for f in (0.1,0.2,0.3):
        cr=np.zeros(len(E),bool)
        for i,(u,w) in enumerate(E):
            o=opp[(min(u,w),max(u,w))]
            if len(o)<2: cr[i]=True; continue
            d=x[w]-x[u]; n1=np.cross(d,x[o[0]]-x[u]); n2=np.cross(x[o[1]]-x[u],d)
            cs=np.clip(n1@n2/np.linalg.norm(n1)/np.linalg.norm(n2),-1,1)
            cr[i]=half*np.sqrt((1-cs)/max(1+cs,1e-12))>f*h
        n2h=n15=nc2=nc15=0; ci=0; ti=0
        for i in range(len(E)):
            e1=E[i]; e2=E[i+1:]
            share=(e2[:,0]==e1[0])|(e2[:,0]==e1[1])|(e2[:,1]==e1[0])|(e2[:,1]==e1[1])
            d,s,t=segnear(x[e1[0]][None],x[e1[1]][None],x[e2[:,0]],x[e2[:,1]])
            dr,_,_=segnear(rest[e1[0]][None],rest[e1[1]][None],rest[e2[:,0]],rest[e2[:,1]])
            keep=(~share)&(dr>=1.5*h)
            anyc=cr[i]|cr[i+1:]
            n2h+=(keep&(d<2*h)).sum(); n15+=(keep&(d<1.5*h)).sum()
            nc2+=(keep&(d<2*h)&anyc).sum(); nc15+=(keep&(d<1.5*h)&anyc).sum()
            inter=keep&(d<h)&(np.minimum(np.minimum(s,1-s),np.minimum(t,1-t))>0)
            ti+=inter.sum(); ci+=(inter&anyc).sum()
        print(fn,f,'creased edges %d of %d'%(cr.sum(),len(E)),'| listed 2h %d -> %d, 1.5h %d -> %d | contacts %d -> %d'%(n2h,nc2,n15,nc15,ti,ci))
