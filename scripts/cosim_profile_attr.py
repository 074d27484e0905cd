#!/usr/bin/env python3
# scripts/cosim_profile_attr.py DIR [DEPTH]: where a verilated unit test's simulation loop spends its time,
# by RTL instance (docs/speed.md, "Session 10: co-simulation speed", reproduce). DIR holds
# rtl_unit_test (the unit verilated with -CFLAGS -g and linked as the test is) and perf.data
# (`perf record -F 25000 ./rtl_unit_test ...`). The samples between the first and the last one in
# a Vfxr_raster_unit___024root function are the loop; a model sample (symbol + offset, nm) goes
# through `addr2line -a -i` and counts at its outermost generated V*.cpp line, under the first
# fxr_raster_unit__DOT__ name on or above that line (instance path cut at DEPTH levels). Prints
# the instances, the samples outside the model, the top lines and the groups by stage.
import collections, json, os, re, subprocess, sys
d = sys.argv[1]; depth = int(sys.argv[2]) if len(sys.argv) > 2 else 4
binp = os.path.join(d, 'rtl_unit_test')
out = subprocess.run(['perf', 'script', '-i', os.path.join(d, 'perf.data'), '-F', 'ip,sym,symoff,dso'], capture_output=True, text=True).stdout
nm = {}
for l in subprocess.run(['nm', '-C', binp], capture_output=True, text=True).stdout.splitlines():
    q = l.split(None, 2)
    if len(q) == 3 and q[0] != "U" and re.match(r"^[0-9a-f]+$", q[0]): nm.setdefault(re.sub(r"\(.*$", "", q[2]), int(q[0], 16))
rows = []
for line in out.splitlines():
    p = line.split(None, 1)
    if not p: continue
    ip = p[0]; rest = p[1] if len(p) > 1 else ''
    rows.append((ip, rest))
idx = [i for i, (ip, s) in enumerate(rows) if '___024root' in s]
a, b = idx[0], idx[-1]
win = rows[a:b+1]
print('samples total', len(rows), 'window', len(win))
model_ips = collections.Counter(); other = collections.Counter()
for ip, s in win:
    m = re.match(r'(.*)\+0x([0-9a-f]+) \(.*rtl_unit_test\)', s)
    if m and (m.group(1).startswith('Vfxr_raster_unit') or m.group(1).startswith('_vl_') or m.group(1).startswith('VL_')) and m.group(1) in nm:
        model_ips['%x' % (nm[m.group(1)] + int(m.group(2), 16))] += 1
    else:
        sym = re.sub(r'\(.*$', '', s).strip()
        other[sym[:90]] += 1
ips = list(model_ips)
# addr2line -a -i: the address, then its inline chain, innermost first
res = subprocess.run(['addr2line', '-a', '-i', '-e', binp] + [hex(int(x, 16)) for x in ips], capture_output=True, text=True).stdout
chains = {}; cur = None
for line in res.splitlines():
    if line.startswith('0x'):
        cur = int(line, 16); chains[cur] = []
    else:
        chains[cur].append(line.strip())
filecache = {}
def lines_of(f):
    if f not in filecache:
        try: filecache[f] = open(f).read().split('\n')
        except Exception: filecache[f] = None
    return filecache[f]
def inst_of(f, ln):
    L = lines_of(f)
    if L is None: return '?' + os.path.basename(f)
    for k in range(ln - 1, max(-1, ln - 400), -1):
        m = re.search(r'fxr_raster_unit__DOT__(\w+)', L[k])
        if m: return m.group(1)
    return 'nodot:' + os.path.basename(f)
by_inst = collections.Counter(); by_line = collections.Counter()
for ip, n in model_ips.items():
    ch = chains.get(int(ip, 16), [])
    vl = [c for c in ch if re.search(r'/V[^/]*\.cpp:\d+', c)]
    if not vl:
        by_inst['runtime:' + (ch[-1] if ch else '?')[-50:]] += n; continue
    f, ln = vl[-1].rsplit(':', 1); ln = int(re.match(r'\d+', ln).group(0))
    name = inst_of(f, ln)
    parts = name.split('__DOT__')
    by_inst['.'.join(parts[:depth])] += n
    by_line[(os.path.basename(f), ln, '.'.join(parts))] += n
tot = len(win)
print('model samples %d (%.1f%%)' % (sum(model_ips.values()), 100*sum(model_ips.values())/tot))
for k, n in by_inst.most_common(45): print('%6.2f%% %6d %s' % (100*n/tot, n, k))
print('--- outside the model (in window)')
for k, n in other.most_common(15): print('%6.2f%% %6d %s' % (100*n/tot, n, k))
print('--- top lines')
for k, n in by_line.most_common(40): print('%6.2f%% %6d %s:%d %s' % (100*n/tot, n, k[0], k[1], k[2][:120]))
print('--- groups')
g = collections.Counter()
for k, n in by_inst.items():
    p = k.split('.')
    if p[0] == 'u_backend' and len(p) > 1 and p[1].startswith('u_'): key = 'u_backend.' + p[1]
    elif p[0] == 'u_backend': key = 'u_backend glue'
    elif p[0].startswith('u_'): key = p[0]
    else: key = 'unit glue:' + ('in_masked' if p[0] == 'in_masked' else 'other')
    g[key] += n
g['harness (outside model, in window)'] = sum(other.values())
for k, n in g.most_common(): print('%6.2f%% %6d %s' % (100*n/tot, n, k))
json.dump({'%s:%d|%s' % k: n for k, n in by_line.items()}, open(os.path.join(d, 'lines.json'), 'w'))
