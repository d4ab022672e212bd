import json,sys,math
for f in sys.argv[1:]:
    d=json.load(open(f))
    objs=d['objects']
    ys=[]
    for o in objs:
        p=o['positions']
        ys.append(sum(q[1] for q in p)/len(p))
    ys_sorted=sorted(ys)
    gaps=[b-a for a,b in zip(ys_sorted,ys_sorted[1:])]
    on_box=[y for y in ys if y>0.19]
    print(f, 'cards', len(ys), 'y min %.4f max %.4f'%(min(ys),max(ys)), 'on box', len(on_box),
          'stack height %.2f mm'%((max(on_box)-min(on_box))*1000 if on_box else 0),
          'median gap %.3f mm'%(sorted(gaps)[len(gaps)//2]*1000), 'min gap %.3f mm'%(min(gaps)*1000))
