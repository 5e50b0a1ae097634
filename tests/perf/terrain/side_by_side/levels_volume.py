# How many fine cells a flush writes in BM_Fusion_Default_GX1_2deg's pattern: the summed-area
# form (the union of the exact footprints) against a levels form (each point splatted
# bilinearly into the 4 nodes of the level whose spacing s = 2^ceil(log2 h) cells, each touched
# node expanded with a tent of half-width s into (2s)^2 fine cells).
import math
G=0.2; nx=ny=150; y_min=-15.0
de=2.0*math.pi/180
def scan(tilt):
    pts=[]
    for k in range(361):
        b=(-90+0.5*k)*math.pi/180
        dx=math.cos(b)*math.cos(tilt); dy=math.sin(b)*math.cos(tilt); dz=-math.sin(tilt)
        r=min(0.87/-dz,40.0)
        # the map frame: reference point at the rear bumper, x from -0.5 body
        x=0.5+r*dx+0.5; y=r*dy
        var=1e-4+2*(r*de)**2
        pts.append((x,y,var))
    return pts
totals=[0,0,0,0]
for start in range(0,16,1):
    exact=set(); nodes={}
    n=0
    for s_ in range(3):
        for (x,y,var) in scan((3.0+(start+s_)%16)*math.pi/180):
            if var<=G*G: continue
            cx=x/G; cy=(y-y_min)/G
            if not(0<=cx<nx and 0<=cy<ny): continue
            n+=1
            h=min(math.sqrt(var)/G,2.0)
            for i in range(int(math.floor(cx-h)),int(math.ceil(cx+h))):
                for j in range(int(math.floor(cy-h)),int(math.ceil(cy+h))):
                    exact.add((i,j))
            s=2**math.ceil(math.log2(h))
            ni=math.floor(cx/s-0.5); nj=math.floor(cy/s-0.5)
            for a in (0,1):
                for b in (0,1):
                    nodes.setdefault((s,ni+a,nj+b),0)
    expand=sum((2*s)**2 for (s,_,_) in nodes)
    fine=set()
    for (s,i,j) in nodes:
        ci=(i+0.5)*s; cj=(j+0.5)*s
        # fine cells whose centre k + 0.5 lies within s of the node's centre
        for a in range(int(math.ceil(ci-s-0.5)),int(math.floor(ci+s-0.5))+1):
            for b in range(int(math.ceil(cj-s-0.5)),int(math.floor(cj+s-0.5))+1):
                if abs(a+0.5-ci)<s and abs(b+0.5-cj)<s: fine.add((a,b))
    totals[0]+=n; totals[1]+=len(exact); totals[2]+=expand; totals[3]+=len(fine)
n,e,x,f=totals
print(f"spread points {n/16:.0f} a flush; summed-area cells {e/n:.2f} a point; levels node expansions {x/n:.1f} fine-cell adds a point, distinct fine cells {f/n:.2f} a point")
