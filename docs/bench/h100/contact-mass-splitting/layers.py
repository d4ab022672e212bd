import json,sys
d=json.load(open(sys.argv[1]))
objs=d['objects'] if 'objects' in d else d
out=[]
for o in objs:
    P=o['positions']; n=int(len(P)**0.5)
    c=[P[r*n+q][1] for r in range(n//2-2,n//2+2) for q in range(n//2-2,n//2+2)]
    sp=max(abs(v[0])+abs(v[1])+abs(v[2]) for v in o['velocities'])
    out.append((o.get('name'),round(sum(c)/len(c),4),round(min(c),4),round(sp,3)))
print(out)
