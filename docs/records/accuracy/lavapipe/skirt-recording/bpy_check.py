import struct, sys, numpy as np
import bpy
print("bpy version", bpy.app.version_string, bpy.app.build_hash)
d=open('/tmp/rec/skirt_skirt.pc2','rb').read()
_,_,NP,_,_,NS=struct.unpack('<12siiffi',d[:32]); pc=np.frombuffer(d[32:],dtype='<f4').reshape(NS,NP,3)
def nn(src,q): return np.sqrt(((q[:,None,:]-src[None,:,:])**2).sum(-1)).min(1)
def cmp(label, V, ref):
    if len(V)==len(ref):
        print(f"  {label}: index-wise max {np.linalg.norm(V-ref,axis=1).max():.3e}")
    print(f"  {label}: nearest-point max {nn(ref,V).max():.3e} (counts {len(V)} vs {len(ref)})")
def uvinfo(me):
    for uvl in me.uv_layers:
        a=np.zeros(len(uvl.data)*2); uvl.data.foreach_get('uv',a); a=a.reshape(-1,2)
        print(f"  UV layer '{uvl.name}' active={uvl.active} active_render={uvl.active_render} loops={len(a)} u[{a[:,0].min():.6f},{a[:,0].max():.6f}] v[{a[:,1].min():.6f},{a[:,1].max():.6f}] distinct uv={len(np.unique(np.round(a,6),axis=0))}")
        # signed UV area per polygon (triangles)
        li=np.zeros(len(me.loops),int); me.loops.foreach_get('vertex_index',li)
        ls=np.zeros(len(me.polygons),int); me.polygons.foreach_get('loop_start',ls)
        if all(p.loop_total==3 for p in me.polygons):
            t=a[(ls[:,None]+np.arange(3))]
            ar=0.5*((t[:,1,0]-t[:,0,0])*(t[:,2,1]-t[:,0,1])-(t[:,2,0]-t[:,0,0])*(t[:,1,1]-t[:,0,1]))
            print(f"    UV signed area: neg {(ar<0).sum()} pos {(ar>0).sum()} total {ar.sum():.4f}")
    print("  attributes:", [(x.name,x.domain,x.data_type) for x in me.attributes])
def verts(obj, world):
    dg=bpy.context.evaluated_depsgraph_get(); ev=obj.evaluated_get(dg); me=ev.to_mesh()
    V=np.zeros(len(me.vertices)*3); me.vertices.foreach_get('co',V); V=V.reshape(-1,3)
    M=np.array(ev.matrix_world)
    ev.to_mesh_clear()
    if world: V=V@M[:3,:3].T+M[:3,3]
    return V

bpy.ops.wm.read_factory_settings(use_empty=True)
print("=== USD import ===", flush=True)
r=bpy.ops.wm.usd_import(filepath='/tmp/rec/skirt.usda')
print("usd_import ->", r, flush=True)
sc=bpy.context.scene
print("scene frame range", sc.frame_start, sc.frame_end, "fps", sc.render.fps, sc.render.fps_base, "current", sc.frame_current)
for o in bpy.data.objects:
    s=f"  {o.name!r} type={o.type} parent={o.parent.name if o.parent else None}"
    if o.type=='MESH': s+=f" verts={len(o.data.vertices)} polys={len(o.data.polygons)} loops={len(o.data.loops)}"
    s+=f" loc={tuple(round(x,4) for x in o.location)} rot={tuple(round(x,4) for x in o.rotation_euler)} mods={[(m.type,m.name) for m in o.modifiers]}"
    s+=f" mats={[m.name for m in o.data.materials] if o.type=='MESH' else ''}"
    print(s)
print("cache files", [(c.name,c.filepath,c.is_sequence, getattr(c,'scale',None)) for c in bpy.data.cache_files])
sk=[o for o in bpy.data.objects if o.type=='MESH' and o.name.startswith('skirt')][0]
print("skirt object", sk.name, "data", sk.data.name)
print("matrix_world", [list(map(lambda x: round(x,5), r)) for r in sk.matrix_world])
for m in sk.modifiers:
    print("  modifier", m.type, m.name, {k:getattr(m,k) for k in ('object_path','read_data','cache_file','use_vertex_interpolation','velocity_scale') if hasattr(m,k)})
print("  shape keys", sk.data.shape_keys, "anim_data", sk.animation_data)
uvinfo(sk.data)
for mat in sk.data.materials:
    if mat: print("  material", mat.name, "use_nodes", mat.use_nodes, "nodes", [n.type for n in mat.node_tree.nodes] if mat.use_nodes else None, "diffuse_color", tuple(mat.diffuse_color))
for f,k in ((sc.frame_start,0),(sc.frame_end,NS-1)):
    sc.frame_set(f); print(f"frame {f}: (PC2 sample {k})")
    Vl=verts(sk,False); Vw=verts(sk,True)
    cmp("local vs PC2", Vl, pc[k])
    # Y-up -> Z-up: (x,y,z)->(x,-z,y)
    ref=pc[k]; refz=np.stack([ref[:,0],-ref[:,2],ref[:,1]],1)
    cmp("world vs PC2 converted Y-up->Z-up (x,-z,y)", Vw, refz)
    cmp("world vs PC2 raw", Vw, ref)
# mesh after frame set - check UV still present on evaluated
dg=bpy.context.evaluated_depsgraph_get(); ev=sk.evaluated_get(dg); me=ev.to_mesh()
print("evaluated mesh at last frame: verts", len(me.vertices), "polys", len(me.polygons), "uv layers", [u.name for u in me.uv_layers]); uvinfo(me); ev.to_mesh_clear()

print("=== OBJ import ===", flush=True)
bpy.ops.wm.read_factory_settings(use_empty=True)
r=bpy.ops.wm.obj_import(filepath='/tmp/rec/skirt.obj')
print("obj_import ->", r)
for o in bpy.data.objects:
    print(f"  {o.name!r} type={o.type} verts={len(o.data.vertices)} polys={len(o.data.polygons)} loops={len(o.data.loops)} rot={tuple(round(x,4) for x in o.rotation_euler)} mats={[m.name for m in o.data.materials]}")
for o in bpy.data.objects:
    if o.type=='MESH' and len(o.data.vertices)>=1000:
        print(" object", o.name); uvinfo(o.data)
        Vw=verts(o,True)
        for k in (0,NS-1):
            ref=pc[k]; refz=np.stack([ref[:,0],-ref[:,2],ref[:,1]],1)
            cmp(f"OBJ world vs PC2[{k}] Z-up", Vw, refz)
