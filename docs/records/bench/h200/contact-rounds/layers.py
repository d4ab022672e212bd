import json,sys
for f in sys.argv[1:]:
    d=json.load(open(f))
    ys=sorted(sum(q[1] for q in o['positions'])/len(o['positions']) for o in d['objects'])
    gaps=[round((b-a)*1000,2) for a,b in zip(ys,ys[1:])]
    print(f.split('/')[-1], 'layer gaps mm', gaps)
