#!/usr/bin/env python3
"""Two builds of galsculpt side by side (docs/benchmarks.md, "Solver changes side by side").

  scripts/bench_versions.py OLD_BINARY NEW_BINARY

On the free ball, the slender bar, the whipped bar and the Charpy bar: `run` alternating old and
new, 3 rounds, default thread count; mean ms a frame (median of the rounds), the largest
difference of the final surfaces' positions, the new build's error in motion against
`--solver reference` at frame 20, and its unconverged frames. Prints Markdown."""
import subprocess, statistics, csv, os, sys, math, tempfile
old, new = sys.argv[1], sys.argv[2]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp(prefix="galsculpt-versions-")
scenes={'free ball':os.path.join(root,'assets/validation/ball.json'),'slender bar':os.path.join(root,'assets/validation/bar.json'),
        'whip (fast)':os.path.join(root,'assets/validation/whip.json'),'charpy (breaks)':os.path.join(root,'assets/scenes/charpy.json')}
frames={'charpy (breaks)':60}
env=dict(os.environ); env.pop('OMP_NUM_THREADS',None); env.pop('GALSCULPT_THREADS',None)
def run(b,scene,n,out,extra=[]):
    subprocess.run([b,'run',scene,'--frames',str(n),'--out',out]+extra,env=env,capture_output=True,check=True)
    rows=list(csv.DictReader(open(out+'/metrics.csv')))
    verts=[tuple(map(float,l.split()[1:4])) for l in open(out+'/final.obj') if l.startswith('v ')]
    return rows,verts
print('| scene | frames | old ms/frame | new ms/frame | new/old | max position difference old vs new (m) | error in motion vs reference at frame 20 | unconverged frames |')
print('| --- | --- | --- | --- | --- | --- | --- | --- |')
for name,scene in scenes.items():
    n=frames.get(name,40)
    run(new,scene,1,tmp+'/abw')  # cache
    o,nw=[],[]
    for r in range(3):
        for b,acc in ((old,o),(new,nw)):
            rows,verts=run(b,scene,n,tmp+'/ab_'+('o' if b==old else 'n'))
            acc.append(statistics.mean(float(x['ms_total']) for x in rows))
            if b==old: vo=verts
            else: vn=verts; rn=rows
    diff=max(max(abs(a-b) for a,b in zip(p,q)) for p,q in zip(vo,vn))
    # error in motion: new at frame 20 vs reference at frame 20, relative to max displacement
    _,v20=run(new,scene,20,tmp+'/ab_m')
    _,r20=run(new,scene,20,tmp+'/ab_r',['--solver','reference'])
    err=max(math.dist(p,q) for p,q in zip(v20,r20))
    unconv=sum(1 for x in rn if x['converged']=='0')
    mo,mn=statistics.median(o),statistics.median(nw)
    print(f'| {name} | {n} | {mo:.1f} | {mn:.1f} | {mn/mo:.2f} | {diff:.1e} | {err:.2e} m | {unconv} |')
