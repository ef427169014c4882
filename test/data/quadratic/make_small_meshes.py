#!/usr/bin/python3
"""Writes the hand-made one- and two-element meshes of this directory that
the readers must refuse or warn of (run here: /usr/bin/python3
make_small_meshes.py):

  mixed_order.msh     a Tet4 (physical volume 'linear') beside a Tet10
                      ('quadratic'): bodies of first and second order (read);
  mixed_order_in_body.msh  the same cells in one physical volume 'part';
  bonded_mixed_order.msh   a Tet10 ('quadratic') on a face of a Tet4
                      ('linear'), sharing its corners: bonded bodies of
                      different orders;
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

def msh(vols, path, physical=None):
    # vols: list of (entity tag, name, gmsh type, the element's nodes): a node
    # is its coordinates, or an int, the number of a node of an earlier
    # element (shared). physical: the physical volume of each entity (tag,
    # name; default: its own, named `name`).
    physical = physical or [(tag, name) for tag, name, typ, X in vols]
    nodes=[]; elems=[]; fresh=[]
    for tag,name,typ,X in vols:
        ids=[]; new=[]
        for x in X:
            if isinstance(x, int):
                ids.append(x)
            else:
                nodes.append(x); ids.append(len(nodes)); new.append(len(nodes))
        elems.append((tag,typ,ids)); fresh.append(new)
    groups=sorted(set(physical))
    out=["$MeshFormat","4.1 0 8","$EndMeshFormat","$PhysicalNames",str(len(groups))]
    for tag,name in groups: out.append('3 %d "%s"'%(tag,name))
    out += ["$EndPhysicalNames","$Entities","0 0 0 %d"%len(vols)]
    for (tag,name,typ,X),(ptag,pname) in zip(vols,physical): out.append("%d 0 0 0 3 3 3 1 %d 0"%(tag,ptag))
    out += ["$EndEntities","$Nodes","%d %d 1 %d"%(len(vols),len(nodes),len(nodes))]
    for (tag,name,typ,X),new in zip(vols,fresh):
        out.append("3 %d 0 %d"%(tag,len(new)))
        out += [str(i) for i in new]
        out += ["%.17g %.17g %.17g"%tuple(nodes[i-1]) for i in new]
    out += ["$EndNodes","$Elements","%d %d 1 %d"%(len(vols),len(vols),len(vols))]
    for i,(tag,typ,ns) in enumerate(elems):
        out.append("3 %d %d 1"%(tag,typ)); out.append("%d "%(i+1)+" ".join(map(str,ns)))
    out += ["$EndElements"]
    open(path,"w").write("\n".join(out)+"\n")

shift=np.array([2.,0,0])
# mixed: a Tet4 in volume 'linear', a Tet10 in volume 'quadratic' (read: bodies may differ in order)
msh([(1,"linear",4,list(C)),(2,"quadratic",11,tet10(C+shift))],"mixed_order.msh")
# the same two cells in one physical volume 'part' (refused: a body has one order)
msh([(1,"linear",4,list(C)),(2,"quadratic",11,tet10(C+shift))],"mixed_order_in_body.msh",
    physical=[(1,"part"),(1,"part")])
# a Tet10 (volume 'quadratic') on the face 1-2-3 of a Tet4 ('linear'), its corners the Tet4's nodes 2, 3, 4
# (refused: bonded bodies of different orders, the face's mid-edge nodes hanging)
D=np.array([[1,0,0],[0,1,0],[0,0,1],[1,1,1]], float)
X=tet10(D); X[0:3]=[2,3,4]
msh([(1,"linear",4,list(C)),(2,"quadratic",11,X)],"bonded_mixed_order.msh")
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
