import struct, numpy as np
from pxr import Usd, UsdGeom, UsdShade, Sdf, Gf
import pxr

def nn(src,q):
    d=np.sqrt(((q[:,None,:]-src[None,:,:])**2).sum(-1)); return d.min(1)
def cc(tris,n):
    par=list(range(n))
    def f(x):
        while par[x]!=x: par[x]=par[par[x]]; x=par[x]
        return x
    for t in tris:
        a=f(t[0])
        for b in t[1:]:
            b=f(b)
            if a!=b: par[b]=a
    r=np.array([f(t[0]) for t in tris]); u,lab=np.unique(r,return_inverse=True); return len(u),lab
P='/tmp/rec/skirt.usda'
stage=Usd.Stage.Open(P)
print("usd version", Usd.GetVersion())
print("upAxis", UsdGeom.GetStageUpAxis(stage), "mpu", UsdGeom.GetStageMetersPerUnit(stage))
print("start/end", stage.GetStartTimeCode(), stage.GetEndTimeCode(), "tcps", stage.GetTimeCodesPerSecond(), "fps", stage.GetFramesPerSecond(), "defaultPrim", stage.GetDefaultPrim().GetPath())
for p in stage.Traverse():
    s=f"{p.GetPath()} {p.GetTypeName()}"
    if p.IsA(UsdGeom.Mesh):
        m=UsdGeom.Mesh(p); s+=f" pts={len(m.GetPointsAttr().Get(0) or [])} faces={len(m.GetFaceVertexCountsAttr().Get())}"
    print(s)
m=UsdGeom.Mesh(stage.GetPrimAtPath('/scene/skirt'))
pa=m.GetPointsAttr()
ts=pa.GetTimeSamples()
print("points timeSampled", pa.ValueMightBeTimeVarying(), "nsamples", len(ts), "range", ts[0], ts[-1])
pts0=np.array(pa.Get(ts[0])); ptsL=np.array(pa.Get(ts[-1]))
fvc=np.array(m.GetFaceVertexCountsAttr().Get()); fvi=np.array(m.GetFaceVertexIndicesAttr().Get())
print("npts", len(pts0), "faceVertexCounts len", len(fvc), "unique counts", np.unique(fvc), "fvi len", len(fvi), "sum fvc", fvc.sum(), "fvi min/max", fvi.min(), fvi.max(), "max<npts", fvi.max()<len(pts0))
print("unused points", len(pts0)-len(np.unique(fvi)))
print("all samples same count", all(len(pa.Get(t))==len(pts0) for t in ts))
print("subdivisionScheme", m.GetSubdivisionSchemeAttr().Get(), "doubleSided", m.GetDoubleSidedAttr().Get(), "orientation", m.GetOrientationAttr().Get())
print("extent samples", len(m.GetExtentAttr().GetTimeSamples()), "extent last", m.GetExtentAttr().Get(ts[-1]))
pvapi=UsdGeom.PrimvarsAPI(m)
for pv in pvapi.GetPrimvars():
    print("primvar", pv.GetPrimvarName(), pv.GetTypeName(), pv.GetInterpolation(), "indexed", pv.IsIndexed(), "elemSize", pv.GetElementSize(), "role", pv.GetTypeName().role)
st=pvapi.GetPrimvar('st')
vals=np.array(st.Get()); idx=np.array(st.GetIndices())
print("st values", len(vals), "indices", len(idx), "idx min/max", idx.min(), idx.max(), "interp", st.GetInterpolation(), "timeVarying", st.ValueMightBeTimeVarying())
print("u range", vals[:,0].min(), vals[:,0].max(), "v range", vals[:,1].min(), vals[:,1].max())
exp={'faceVarying':len(fvi),'vertex':len(pts0),'varying':len(pts0),'uniform':len(fvc),'constant':1}[st.GetInterpolation()]
n=len(idx) if st.IsIndexed() else len(vals)
print("UV element count", n, "expected", exp, "OK" if n==exp else "MISMATCH")
fl=st.ComputeFlattened()
print("flattened len", len(fl))
# UV islands: connected components on faces sharing st index
tri=idx.reshape(-1,3)
ncomp,lab=cc(tri,len(vals))
print("UV islands (by shared st index)", ncomp)
for c in range(ncomp):
    ii=np.unique(tri[lab==c]); v=vals[ii]
    print(f"  island {c}: tris={np.sum(lab==c)} uv-verts={len(ii)} u[{v[:,0].min():.6f},{v[:,0].max():.6f}] v[{v[:,1].min():.6f},{v[:,1].max():.6f}]")
# geometric components
ptri=fvi.reshape(-1,3)
nc2,lab2=cc(ptri,len(pts0))
print("geometric shells", nc2, [int(np.sum(lab2==c)) for c in range(nc2)])
# does each position vertex map to a single UV? (seams)
pairs=np.unique(np.stack([fvi,idx],1),axis=0)
print("distinct (point,uv) pairs", len(pairs), "points with >1 UV", int(np.sum(np.bincount(pairs[:,0])>1)))
# UV area / flipped
uv=vals[tri]; a=0.5*((uv[:,1,0]-uv[:,0,0])*(uv[:,2,1]-uv[:,0,1])-(uv[:,2,0]-uv[:,0,0])*(uv[:,1,1]-uv[:,0,1]))
print("UV tri signed area: min", a.min(), "max", a.max(), "neg", int((a<0).sum()), "zero", int((abs(a)<1e-12).sum()), "total", a.sum())
nm=m.GetNormalsAttr()
print("normals interp", m.GetNormalsInterpolation(), "nsamples", len(nm.GetTimeSamples()), "len@last", len(nm.Get(ts[-1])))
N=np.array(nm.Get(ts[-1])); print("normal length min/max", np.linalg.norm(N,axis=1).min(), np.linalg.norm(N,axis=1).max())
# check normals vs geometric face normals orientation
P=ptsL; fn=np.cross(P[ptri[:,1]]-P[ptri[:,0]],P[ptri[:,2]]-P[ptri[:,0]])
vn=np.zeros_like(P); 
for k in range(3): np.add.at(vn,ptri[:,k],fn)
vn/=np.linalg.norm(vn,axis=1,keepdims=True)+1e-30
print("dot(stored normal, area-weighted face normal) min/mean", (vn*N).sum(1).min(), (vn*N).sum(1).mean())
mb=UsdShade.MaterialBindingAPI(m.GetPrim()); mat,rel=mb.ComputeBoundMaterial()
print("bound material", mat.GetPath() if mat else None)
print("displayColor", m.GetDisplayColorAttr().Get(), "interp", m.GetDisplayColorPrimvar().GetInterpolation())
# PC2
d=open('/tmp/rec/skirt_skirt.pc2','rb').read()
hdr=struct.unpack('<12siiffi',d[:32]); print("PC2 header", hdr, "file size", len(d), "expected", 32+hdr[2]*hdr[5]*12)
np_,ns=hdr[2],hdr[5]
arr=np.frombuffer(d[32:],dtype='<f4').reshape(ns,np_,3)
for name,usdp,pcp in [("first",pts0,arr[0]),("last",ptsL,arr[-1])]:
    if len(usdp)==np_:
        dd=np.linalg.norm(usdp-pcp,axis=1); print(f"{name}: same count, index-wise max dist {dd.max():.3e} mean {dd.mean():.3e}")
    dn=nn(pcp,usdp); print(f"{name}: nearest max dist {dn.max():.3e}")
# per-frame over all
if len(pts0)==np_:
    mx=max(np.linalg.norm(np.array(pa.Get(t))-arr[i],axis=1).max() for i,t in enumerate(ts))
    print("max over all", ns, "frames index-wise", mx)
print("world xform skirt identity?", m.ComputeLocalToWorldTransform(ts[-1])==Gf.Matrix4d(1))
