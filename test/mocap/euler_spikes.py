#!/usr/bin/python3
"""Angular velocity of BVH joints two ways, to tell Euler-angle artifacts from the motion:

  euler-rate:     the joint's Euler angles (each unwrapped at +-180 degrees) differentiated by
                  central differences, turned into the angular velocity (relative to the parent,
                  body axes) through the angles' rate matrix, as mbk bag does;
  rotation-group: the rotation between frames f-1 and f+1 (R_{f-1}^T R_{f+1}, from the
                  orientations themselves, whatever angles represent them), its angle over 2 dt.

An artifact of a representation flip (near gimbal lock two angles jump together) shows in the
first and not in the second; a jump in the recorded orientation shows in both (the second
saturates at pi / (2 dt) for a half turn between frames).

usage: euler_spikes.py FILE.bvh JOINT [JOINT ...]   (numpy; /usr/bin/python3)
"""
import numpy as np, sys
def parse(path):
    with open(path) as f: txt=f.read().split()
    i=0; segs=[]; stack=[]; ch=0
    while txt[i]!='MOTION':
        t=txt[i]
        if t in('ROOT','JOINT'):
            segs.append({'name':txt[i+1],'parent':stack[-1] if stack else -1}); i+=2; continue
        if t=='{':
            if segs and (not stack or stack[-1]!=len(segs)-1) and txt[i-1]!='Site': stack.append(len(segs)-1)
            elif txt[i-1]=='Site': stack.append(-2)
            i+=1; continue
        if t=='}': stack.pop(); i+=1; continue
        if t=='CHANNELS':
            n=int(txt[i+1]); segs[-1]['ch']=txt[i+2:i+2+n]; segs[-1]['col']=ch; ch+=n; i+=2+n; continue
        i+=1
    nf=int(txt[i+2]); dt=float(txt[i+5]); data=np.array(txt[i+6:],float).reshape(nf,ch)
    for s in segs: s["name"]=s["name"].strip()
    return segs,data,dt
def R(axis,a):
    c,s=np.cos(a),np.sin(a)
    if axis=='X': return np.array([[1,0,0],[0,c,-s],[0,s,c]])
    if axis=='Y': return np.array([[c,0,s],[0,1,0],[-s,0,c]])
    return np.array([[c,-s,0],[s,c,0],[0,0,1]])
def local(seg,row):
    M=np.eye(3)
    for k,c in enumerate(seg['ch']):
        if c.endswith('rotation'): M=M@R(c[0],np.radians(row[seg['col']+k]))
    return M
def logm(M):
    c=np.clip((np.trace(M)-1)/2,-1,1); th=np.arccos(c)
    if th<1e-12: return np.zeros(3)
    w=np.array([M[2,1]-M[1,2],M[0,2]-M[2,0],M[1,0]-M[0,1]])/(2*np.sin(th))
    return w*th
def speeds(segs,data,dt,name):
    """The joint's angular speed (rad/s) at frames 1..n-2: (euler-rate, rotation-group)."""
    j=[s['name'] for s in segs].index(name); s=segs[j]
    rot=[(k,c[0]) for k,c in enumerate(s['ch']) if c.endswith('rotation')]
    ang=np.radians(data[:,[s['col']+k for k,_ in rot]])
    ang=np.unwrap(ang,axis=0)
    # Euler-rate angular velocity (relative to the parent, in the body frame) via central differences
    n=len(data); we=[]; wr=[]
    for f in range(1,n-1):
        rates=(ang[f+1]-ang[f-1])/(2*dt)
        # body-frame omega = sum over k of (R_{k+1..}^T axis_k) rate_k
        w=np.zeros(3); M=np.eye(3)
        for k in reversed(range(len(rot))):
            e=np.zeros(3); e['XYZ'.index(rot[k][1])]=1
            w+=M.T@e*rates[k]; M=R(rot[k][1],ang[f,k])@M
        we.append(np.linalg.norm(w))
        A=local(s,data[f-1]); B=local(s,data[f+1])
        wr.append(np.linalg.norm(logm(A.T@B))/(2*dt))
    return np.array(we),np.array(wr),ang
def main(argv):
    segs,data,dt=parse(argv[1])
    for name in argv[2:]:
        we,wr,ang=speeds(segs,data,dt,name)
        print("%s %s: euler-rate max %.1f rad/s, >20: %.1f%%; rotation-group max %.1f, >20: %.1f%%; worst frame %d angles %s"%(argv[1].split('/')[-1],name,we.max(),100*np.mean(we>20),wr.max(),100*np.mean(wr>20),we.argmax()+1,np.degrees(ang[we.argmax()+1]).round(1)))
if __name__=="__main__":
    main(sys.argv)
