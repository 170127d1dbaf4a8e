#!/usr/bin/env python3
"""Honesty checks for the contact2d pFUnit fallback (Python standard library only).

  check_selftest.py failures EXE PF_FILE
      Run EXE (built from PF_FILE = funit_selftest_fail.pf, whose assertions
      fail on purpose) and require: a non-zero exit status; every test carrying
      an "! EXPECT-FAIL" comment reported FAIL with "<file>.pf:<line>: <kind>
      failure:" for the line of the statement following the comment, and the
      expected/actual values and texts listed there; every other test PASS;
      a correct summary; and no output from code after a failed assertion.

  check_selftest.py rejects PREPROCESSOR
      Run the preprocessor on small invalid .pf files and require a non-zero
      exit status and an error naming "<file>.pf:<line>"; a valid control file
      must be accepted.

Exit status 0 when every check holds, 1 otherwise.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

VALUE = r'("[^"]*"|\S+?)'
PATTERNS = {
    'expected': r'expected %s but found ' % VALUE,
    'found': r' but found %s(?:\s|$)' % VALUE,
    'lhs': r'expected %s to be ' % VALUE,
    'rhs': r' (?:less|greater) than (?:or equal to )?%s(?:\s|$)' % VALUE,
}


def same_value(want, got):
    """Numbers compare numerically (1.5 == 1.5000000000000000), the rest literally."""
    try:
        w, g = float(want), float(got)
    except ValueError:
        return want.strip('"') == got.strip('"')
    return (w != w and g != g) or w == g


def parse_expectations(pf_path):
    """Return ([test names in order], {test: (line, kind, [(key, value)])})."""
    tests, expect, pending, want_name = [], {}, None, False
    with open(pf_path) as f:
        lines = f.readlines()
    for n, line in enumerate(lines, 1):
        s = line.strip()
        if re.match(r'@test\b', s, re.I):
            want_name = True
        elif want_name and re.match(r'subroutine\s+\w+', s, re.I):
            tests.append(re.match(r'subroutine\s+(\w+)', s, re.I).group(1))
            want_name = False
        elif s.startswith('! EXPECT-FAIL'):
            words = shlex.split(s[len('! EXPECT-FAIL'):])
            pending = (words[0], [tuple(w.split('=', 1)) for w in words[1:]])
        elif pending and s and not s.startswith('!'):
            expect[tests[-1]] = (n, pending[0], pending[1])
            pending = None
    return tests, expect


def check_failures(exe, pf_path):
    base = os.path.basename(pf_path)
    suite = os.path.splitext(base)[0]
    tests, expect = parse_expectations(pf_path)
    run = subprocess.run([exe], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True, timeout=300)
    out = run.stdout
    print(out)
    problems = []
    if run.returncode == 0:
        problems.append('the failing self-test exited with status 0')
    blocks = {}  # test name -> output lines of that test
    current = None
    for line in out.splitlines():
        m = re.match(r'\[ RUN      \] %s::(\w+)$' % suite, line)
        if m:
            current = m.group(1)
            blocks[current] = []
        elif current:
            blocks[current].append(line)
    for t in tests:
        block = blocks.get(t)
        verdict = 'FAIL' if t in expect else 'PASS'
        if block is None or '[     %s ] %s::%s' % (verdict, suite, t) not in block:
            problems.append('%s: expected verdict %s' % (t, verdict))
            continue
        if t not in expect:
            continue
        lineno, kind, fields = expect[t]
        if kind == 'throw':
            candidates = block
        else:
            marker = '%s:%d: %s failure:' % (base, lineno, kind)
            candidates = [l for l in block if marker in l]
            if not candidates:
                problems.append('%s: no line containing "%s"' % (t, marker))
                continue
        text = candidates[0] if kind != 'throw' else '\n'.join(block)
        for key, want in fields:
            if key in PATTERNS:
                m = re.search(PATTERNS[key], text)
                if not m or not same_value(want, m.group(1)):
                    problems.append('%s: %s should be %s in: %s' % (t, key, want, text))
            elif key == 'index':
                if 'at index %s' % want not in text:
                    problems.append('%s: missing "at index %s" in: %s' % (t, want, text))
            elif key == 'count':
                if '%s elements differ' % want not in text:
                    problems.append('%s: missing "%s elements differ" in: %s' % (t, want, text))
            elif key == 'text':
                if want not in text:
                    problems.append('%s: missing "%s" in: %s' % (t, want, text))
            else:
                problems.append('%s: unknown EXPECT-FAIL key "%s"' % (t, key))
    summary = '%s: %d tests, %d failed' % (suite, len(tests), len(expect))
    if summary not in out:
        problems.append('missing summary "%s"' % summary)
    if 'MUST NOT BE REACHED' in out:
        problems.append('code after a failed assertion was executed')
    return problems


VALID = """module {stem}
   use funit
   implicit none
contains
   @test
   subroutine test_ok()
      @assertTrue(.true.)
   end subroutine test_ok
end module {stem}
"""

# (file stem, text of the bad line or None for "whole file", line expected in the error)
INVALID = [
    ('bad_unknown_directive', '      @assertNotEqual(1, 2)', 7),
    ('bad_test_options', None, 5),
    ('bad_trailing_comment', '      @assertTrue(.true.) ! comment', 7),
    ('bad_unbalanced', '      @assertEqual(1, f(2)', 7),
    ('bad_too_few_args', '      @assertEqual(1)', 7),
    ('bad_relative_without_tolerance', '      @assertRelativelyEqual(1.0, 1.0)', 7),
    ('bad_continued_directive', '      @assertEqual(1, &', 7),
    ('bad_module_name', None, 1),
    # pFUnit 4.14 cannot build it ("Name at (1) is too long": <module>_suite has 64 characters)
    ('bad_module_name_of_58_characters_that_pfunit_cannot_build_', None, 1),
]


def check_rejects(preprocessor):
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        def run(stem, text):
            pf = os.path.join(tmp, stem + '.pf')
            with open(pf, 'w') as f:
                f.write(text)
            return subprocess.run([sys.executable, preprocessor, pf, pf + '.F90', pf + '_driver.F90'],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  universal_newlines=True, timeout=60)
        ok = run('good_control', VALID.format(stem='good_control'))
        if ok.returncode != 0:
            problems.append('valid control file rejected: ' + ok.stderr)
        for stem, bad_line, lineno in INVALID:
            text = VALID.format(stem=stem).splitlines()
            if stem == 'bad_test_options':
                text[4] = '   @test(npes=[1])'
            elif stem == 'bad_module_name':
                text[0] = 'module some_other_name'
            elif stem == 'bad_continued_directive':
                # pFUnit 4.14 rejects '&'-continued directives; so must the fallback
                text[6] = bad_line
                text[7] = '           1)'
            elif bad_line is not None:
                text[6] = bad_line
            res = run(stem, '\n'.join(text) + '\n')
            where = '%s.pf:%d:' % (stem, lineno)
            print('%s -> exit %d: %s' % (stem, res.returncode, res.stderr.strip()))
            if res.returncode == 0 or where not in res.stderr:
                problems.append('%s: expected a hard error naming %s' % (stem, where))
    return problems


def main(argv):
    if len(argv) == 4 and argv[1] == 'failures':
        problems = check_failures(argv[2], argv[3])
    elif len(argv) == 3 and argv[1] == 'rejects':
        problems = check_rejects(argv[2])
    else:
        sys.stderr.write(__doc__)
        return 2
    for p in problems:
        print('SELFTEST PROBLEM: ' + p)
    print('fallback self-test: %s' % ('FAILED' if problems else 'OK'))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
