#!/usr/bin/python3
"""Writes the hand-made one- and two-element meshes of this directory that
the readers must refuse or warn of (run here: /usr/bin/python3
make_small_meshes.py):

  mixed_order.msh     a Tet4 (physical volume 'linear') beside a Tet10
                      ('quadratic'): first and second order mixed;
  inverted_tet10.msh  a Tet10 with corners 1 and 2 swapped (det J < 0);
  folded_tet10.msh    a Tet10 whose mid-edge node of edge 0-1 lies at 0.85
                      along it (0.35 of the edge from the midpoint): det J
                      < 0 at corner 1 while the node stays on its edge;
  curved_tet10.msh    a Tet10 whose mid-edge node of edge 0-1 is moved off
                      its edge by 0.3 of its length, outward within the plane
                      of face 0-1-2: read, with a warning (det J = 1 + 1.2
                      lambda_1 > 0; moved inward by as much it would fold at
                      corner 1: det J = 1 - 1.2 there).
"""
import numpy as np
# reference Tet10 in Gmsh order on the unit tetrahedron
C = np.array([[0,0,0],[1,0,0],[0,1,0],[0,0,1]], float)
EDGES = [(0,1),(1,2),(2,0),(3,0),(3,2),(3,1)]
def tet10(C):
    return [c for c in C] + [0.5*(C[a]+C[b]) for a,b in EDGES]

def msh(vols, path):
    # vols: list of (physical tag, name, gmsh type, list of node coords per element (one element))
    nodes=[]; elems=[]
    for tag,name,typ,X in vols:
        first=len(nodes)+1
        nodes += list(X)
        elems.append((tag,typ,list(range(first, first+len(X)))))
    out=["$MeshFormat","4.1 0 8","$EndMeshFormat","$PhysicalNames",str(len(vols))]
    for tag,name,typ,X in vols: out.append('3 %d "%s"'%(tag,name))
    out += ["$EndPhysicalNames","$Entities","0 0 0 %d"%len(vols)]
    for tag,name,typ,X in vols: out.append("%d 0 0 0 3 3 3 1 %d 0"%(tag,tag))
    out += ["$EndEntities","$Nodes","%d %d 1 %d"%(len(vols),len(nodes),len(nodes))]
    k=0
    for (tag,name,typ,X) in vols:
        out.append("3 %d 0 %d"%(tag,len(X)))
        out += [str(k+i+1) for i in range(len(X))]
        out += ["%.17g %.17g %.17g"%tuple(x) for x in X]
        k+=len(X)
    out += ["$EndNodes","$Elements","%d %d 1 %d"%(len(vols),len(vols),len(vols))]
    for i,(tag,typ,ns) in enumerate(elems):
        out.append("3 %d %d 1"%(tag,typ)); out.append("%d "%(i+1)+" ".join(map(str,ns)))
    out += ["$EndElements"]
    open(path,"w").write("\n".join(out)+"\n")

shift=np.array([2.,0,0])
# mixed: a Tet4 in volume 'linear', a Tet10 in volume 'quadratic'
msh([(1,"linear",4,list(C)),(2,"quadratic",11,tet10(C+shift))],"mixed_order.msh")
# inverted: corners 1 and 2 swapped (and the mid-edge nodes with them)
Ci=C[[0,2,1,3]]
msh([(1,"part",11,tet10(Ci))],"inverted_tet10.msh")
# folded: the mid-edge node of edge 0-1 moved along it to 0.85 (0.35 of the edge from its midpoint)
X=tet10(C); X[4]=np.array([0.85,0,0])
msh([(1,"part",11,X)],"folded_tet10.msh")
# curved: the mid-edge node of edge 0-1 moved off its edge by 0.3 of its length, outward in face 0-1-2's plane
# (det J = 1 + 1.2 lambda_1 stays positive)
X=tet10(C); X[4]=np.array([0.5,-0.3,0])
msh([(1,"part",11,X)],"curved_tet10.msh")
