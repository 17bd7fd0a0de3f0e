"""bench/read_once.py — CPU time (user + system, from the children's getrusage) and wall time of whole
polydec commands run by two binaries in turn (e.g. main's and a branch's), N interleaved rounds, medians
and the ratio NEW/OLD per command (docs/benchmarks.md, "Reading a .msh file once"). Each binary runs
with LD_LIBRARY_PATH set to its own folder.
Usage: python3 bench/read_once.py OLD/polydec NEW/polydec N "info a.msh" "convert b.msh out.ovm" ..."""
import os, resource, subprocess, sys, time, statistics
old, new, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
cmds = [c.split() for c in sys.argv[4:]]
env_old = dict(os.environ, LD_LIBRARY_PATH=os.path.dirname(old))
env_new = dict(os.environ, LD_LIBRARY_PATH=os.path.dirname(new))
res = {}
def run(exe, env, cmd):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN); t0 = time.perf_counter()
    subprocess.run([exe] + cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime + r1.ru_stime) - (r0.ru_utime + r0.ru_stime), time.perf_counter() - t0
print("load", os.getloadavg())
for i in range(n):
    for cmd in cmds:
        for tag, exe, env in (("old", old, env_old), ("new", new, env_new)):
            res.setdefault((" ".join(cmd), tag), []).append(run(exe, env, cmd))
print("load", os.getloadavg())
for cmd in cmds:
    c = " ".join(cmd)
    o = [statistics.median(x[k] for x in res[(c, "old")]) for k in (0, 1)]
    w = [statistics.median(x[k] for x in res[(c, "new")]) for k in (0, 1)]
    print(f"{c}: CPU old {o[0]*1e3:.0f} ms new {w[0]*1e3:.0f} ms ratio new/old {w[0]/o[0]:.3f}; wall old {o[1]*1e3:.0f} new {w[1]*1e3:.0f} ratio {w[1]/o[1]:.3f}")
