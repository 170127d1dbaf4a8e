#!/usr/bin/env python3
"""The guard of a restructure: every shipped deck (inputs/*.nml) run with a base binary and with a
new one, explicit (solver:max_steps = 3000) and --static, one thread; what each prints (stdout and
stderr, less the timing lines) and the two HDF5 files (every dataset and every attribute, bit for
bit, less the wall-clock attributes) compared. Prints one line per run and ALL SAME, or the
differences and exit 1 (docs/extending.md, "Guarding a restructure").

    /usr/bin/python3 tools/h5same.py --base OLD/bin/contact2d NEW/bin/contact2d [deck-substring ...]

OLD is typically a build of the commit before the change (git worktree add ../old HEAD~1, then
cmake there); both must be builds with the same flags, since another -march rounds otherwise.
"""
import os, subprocess, sys, tempfile, glob
import h5py, numpy as np
SKIP_ATTR = ('wall', 'time_', 'timing', 'seconds', 'clock', 'date', 'host', 'version', 'pid', 'build', 'threads', 'command', 'elapsed', 'rate')
def run(binary, deck, out, extra):
    env = dict(os.environ, OMP_NUM_THREADS='1')
    p = subprocess.run([binary, deck, '-o', out, '--force'] + extra, env=env, capture_output=True, text=True)
    noisy = ('wall time', 'element-steps', 'ETA', 'threads', ' -> ', 'set-up', 'static solve ')
    text = [l for l in (p.stdout + p.stderr).replace(out, 'OUT').splitlines() if not any(n in l for n in noisy)]
    return p.returncode, text
def walk(f):
    items = {}
    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            items['D:' + name] = obj[()]
        for k, v in obj.attrs.items():
            items['A:' + name + '@' + k] = v
    for k, v in f.attrs.items():
        items['A:/@' + k] = v
    f.visititems(visit)
    return items
def same(a, b):
    try:
        a = np.asarray(a); b = np.asarray(b)
        if a.shape != b.shape or a.dtype != b.dtype: return False
        if a.dtype.kind == 'f': return a.tobytes() == b.tobytes()
        return np.array_equal(a, b)
    except Exception:
        return str(a) == str(b)
def main():
    import argparse
    ap = argparse.ArgumentParser(description='bitwise comparison of two contact2d builds on the shipped decks')
    ap.add_argument('--base', required=True, help='the base contact2d (e.g. the previous commit built apart)')
    ap.add_argument('new', help='the new contact2d')
    ap.add_argument('patterns', nargs='*', help='only the decks whose path contains one of these')
    args = ap.parse_args()
    global BASE
    BASE = os.path.abspath(args.base)
    binary = os.path.abspath(args.new); pats = args.patterns
    decks = sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'inputs', '*.nml')))
    bad = 0
    for deck in decks:
        if pats and not any(p in deck for p in pats): continue
        for mode in ([], ['--static']):
            extra = ['--set', 'solver:max_steps=3000'] + mode if not mode else mode
            with tempfile.TemporaryDirectory() as d:
                a, b = os.path.join(d, 'a.h5'), os.path.join(d, 'b.h5')
                ra, ea = run(BASE, deck, a, extra); rb, eb = run(binary, deck, b, extra)
                tag = os.path.basename(deck) + (' --static' if mode else '')
                if ra != rb or ea != eb:
                    import difflib
                    d = [l for l in difflib.unified_diff(ea, eb, 'baseline', 'new', lineterm='', n=0)][2:12]
                    print(f'DIFF {tag}: exit {ra} vs {rb}; printed text differs:\n  ' + '\n  '.join(d)); bad += 1; continue
                if not os.path.exists(a):
                    print(f'same {tag} (both exit {ra}, no file)'); continue
                with h5py.File(a) as fa, h5py.File(b) as fb:
                    ia, ib = walk(fa), walk(fb)
                diffs = []
                for k in sorted(set(ia) | set(ib)):
                    if k.startswith('A:') and any(s in k.split('@')[-1] for s in SKIP_ATTR): continue
                    if k not in ia or k not in ib: diffs.append(k + (' only in new' if k in ib else ' only in baseline')); continue
                    if not same(ia[k], ib[k]): diffs.append(k)
                if diffs:
                    bad += 1; print(f'DIFF {tag}: ' + '; '.join(diffs[:8]) + (f' (+{len(diffs)-8})' if len(diffs) > 8 else ''))
                else:
                    print(f'same {tag} ({len(ia)} items)')
    print('ALL SAME' if bad == 0 else f'{bad} DIFFERENT'); sys.exit(1 if bad else 0)
main()
