#!/usr/bin/env python3
"""Fallback for pFUnit 4's `funitproc`, covering only the subset contact2d uses.

Usage:  funitproc_fallback.py INPUT.pf OUTPUT_MODULE.F90 OUTPUT_DRIVER.F90

INPUT.pf must be a module-style pFUnit test file whose module name equals the
file stem (pFUnit >= 4.7 enforces the same) and which contains `use funit`.
Supported annotations -- anything else starting with '@' is a hard error
reported as "file.pf:LINE: error: ...":

  @test                 marks the next `subroutine name()` as a test.  Plain
                        `@test` or `@test()` only: options such as
                        @test(ifdef=..., npes=..., timeout=...) are rejected,
                        because silently ignoring them could change verdicts.
  @before, @after       at most one each; run around every test.
  @assertEqual, @assertRelativelyEqual, @assertTrue, @assertFalse,
  @assertLessThan, @assertLessThanOrEqual,
  @assertGreaterThan, @assertGreaterThanOrEqual
                        arguments are passed through unchanged, exactly as
                        funitproc does:  call assertX(<args>, &
                          location=SourceLocation('file.pf', LINE))
                          if (anyExceptions()) return
A directive must fit on one line: a trailing '&' is an error, because pFUnit
4.14 rejects '&'-continued @-directives ("Invalid character in name") and the
two paths must accept the same files (compute long arguments into local
variables first).  Any text after the closing parenthesis (including a
trailing '! comment') is an error.  LINE is the line
holding the '@'.  The module keeps a 1:1 line mapping with the .pf plus
`#line` markers, so compiler diagnostics point into the .pf file.

The driver program runs, for each @test in file order: @before; if it did not
fail, the test and then @after (pFUnit's TestCase%runBare order).  It prints
PASS/FAIL per test and a summary, and ends with `stop 1` (exit status 1) on
any failure.
"""
import os
import re
import sys

ASSERTS = {  # lower-case directive -> (procedure in module funit, minimum number of arguments)
    'assertequal': ('assertEqual', 2),
    'assertrelativelyequal': ('assertRelativelyEqual', 3),
    'asserttrue': ('assertTrue', 1),
    'assertfalse': ('assertFalse', 1),
    'assertlessthan': ('assertLessThan', 2),
    'assertlessthanorequal': ('assertLessThanOrEqual', 2),
    'assertgreaterthan': ('assertGreaterThan', 2),
    'assertgreaterthanorequal': ('assertGreaterThanOrEqual', 2),
}
BREAK = '\0'  # marks a physical line break inside a joined, continued directive


class PfError(Exception):
    pass


def error(path, lineno, msg):
    raise PfError('%s:%d: error: %s' % (path, lineno, msg))


def split_top_level(text):
    """Split at commas outside quotes/brackets.  Returns (pieces, rest) where
    rest is the text after an unmatched closing bracket, or None if the
    brackets/quotes do not balance."""
    pieces, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            if c == quote:
                quote = None  # a doubled quote simply re-opens on the next char
        elif c in '\'"':
            quote = c
        elif c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
            if depth < 0:
                pieces.append(text[start:i])
                return pieces, text[i + 1:]
        elif c == ',' and depth == 0:
            pieces.append(text[start:i])
            start = i + 1
    return None, None


def join_directive(path, lines, start):
    """The directive at lines[start]; a trailing '&' (continuation) is an error, as in
    pFUnit 4.14.  Returns (text, index after it)."""
    seg = lines[start].strip()
    if seg.rstrip().endswith('&'):
        error(path, start + 1, '"&"-continued @-directive: pFUnit 4.14 rejects it (Invalid '
              'character in name); put the directive on one line')
    return seg.rstrip(), start + 1


def translate(path, lines):
    """Return (module source, test names, before, after)."""
    base = os.path.basename(path)
    stem = os.path.splitext(base)[0]
    out = ['#line 1 "%s"\n' % path]
    module, uses_funit = None, False
    tests, fixtures = [], {'before': None, 'after': None}
    pending = None  # (directive, line) waiting for its subroutine statement
    i = 0
    while i < len(lines):
        line, lineno = lines[i], i + 1
        s = line.strip()
        if s.startswith('@'):
            text, nxt = join_directive(path, lines, i)
            m = re.match(r'@(\w+)(.*)$', text, re.S)
            if not m:
                error(path, lineno, 'malformed directive %r' % s)
            key, rest = m.group(1).lower(), m.group(2).replace(BREAK, ' ').strip()
            if module is None:
                error(path, lineno, 'directive before the "module" statement: only module-style '
                      'test files are supported')
            if pending:
                error(path, lineno, '@%s at line %d must be followed by a subroutine statement'
                      % pending)
            if key in ('test', 'before', 'after'):
                allowed = ('', '()') if key == 'test' else ('',)
                if rest.replace(' ', '') not in allowed:
                    error(path, lineno, '"@%s%s" is not supported by the fallback (only a plain '
                          '@%s)' % (m.group(1), rest, key))
                if key != 'test' and fixtures[key]:
                    error(path, lineno, 'more than one @%s' % key)
                pending = (key, lineno)
                out.extend('!' + l for l in lines[i:nxt])  # keep the 1:1 line mapping
            elif key in ASSERTS:
                out.extend(expand_assert(path, base, lineno, nxt, line, m.group(1), m.group(2)))
            else:
                error(path, lineno, 'unsupported directive "@%s" (supported: @test, @before, '
                      '@after, @%s)' % (m.group(1), ', @'.join(v[0] for v in ASSERTS.values())))
            i = nxt
            continue
        i += 1
        out.append(line)
        if pending and s and not s.startswith('!'):
            m = re.match(r'subroutine\s+(\w+)\s*(\(\s*\))?\s*(!.*)?$', s, re.I)
            if not m:
                error(path, lineno, 'expected "subroutine <name>()" without arguments after @%s '
                      '(line %d); TestCase-style tests with arguments are not supported' % pending)
            name = m.group(1)
            if pending[0] == 'test':
                if name.lower() in (t.lower() for t in tests):
                    error(path, lineno, 'duplicate test "%s"' % name)
                tests.append(name)
            else:
                fixtures[pending[0]] = name
            pending = None
            continue
        m = re.match(r'\s*module\s+(\w+)(.*)$', line, re.I)
        if m and m.group(1).lower() not in ('procedure', 'function', 'subroutine'):
            if module is not None:
                error(path, lineno, 'only one module per .pf file is supported')
            if m.group(2).strip():
                error(path, lineno, 'the module statement must be exactly "module <name>" '
                      '(pFUnit does not recognise it otherwise)')
            module = m.group(1)
            if len(module) > 57:
                error(path, lineno, 'module "%s" has %d characters: pFUnit 4.14 names its suite '
                      '"<module>_suite", a Fortran name of at most 63 characters, so the module (and '
                      'the file stem) may have at most 57' % (module, len(module)))
            if module != stem:
                error(path, lineno, 'module "%s" must be named like the file stem "%s" '
                      '(pFUnit requires this too)' % (module, stem))
        if re.match(r'\s*use\s*(::)?\s*funit\b', line, re.I):
            uses_funit = True
    if pending:
        error(path, pending[1], '@%s is not followed by a subroutine' % pending[0])
    if module is None:
        error(path, 1, 'no "module <name>" statement: only module-style test files are supported')
    if not uses_funit:
        error(path, 1, 'the test module must "use funit"')
    if not tests:
        error(path, len(lines), 'no @test found')
    return ''.join(out), tests, fixtures['before'], fixtures['after']


def expand_assert(path, base, lineno, nxt, line, name, rest):
    """Translate one (possibly continued) @assert directive like funitproc."""
    fname, nmin = ASSERTS[name.lower()]
    body = rest.lstrip(' \t' + BREAK)
    if not body.startswith('('):
        error(path, lineno, 'expected "(" after @%s' % name)
    args, trailing = split_top_level(body[1:])
    if args is None:
        error(path, lineno, 'unbalanced parentheses or quotes in @%s (a trailing comment or a '
              'missing "&" continuation?)' % name)
    if trailing.replace(BREAK, '').strip():
        error(path, lineno, 'unexpected text after @%s(...): the directive must end the line '
              '(no trailing comments)' % name)
    nargs = 0 if not ','.join(args).replace(BREAK, '').strip() else len(args)
    if nargs < nmin:
        error(path, lineno, '@%s needs at least %d argument(s), found %d' % (name, nmin, nargs))
    indent = line[:len(line) - len(line.lstrip())]
    call = ','.join(args).replace(BREAK, '&\n%s&' % indent)  # keep the user's line breaks
    return ['#line %d "%s"\n' % (lineno, path),
            '%scall %s(%s, &\n' % (indent, fname, call),
            "%s& location=SourceLocation('%s', %d))\n" % (indent, base, lineno),
            '%sif (anyExceptions()) return\n' % indent,
            '#line %d "%s"\n' % (nxt + 1, path)]


def driver(path, module, tests, before, after):
    base = os.path.basename(path)
    used = tests + [p for p in (before, after) if p]
    out = ['! Generated by funitproc_fallback.py from %s -- do not edit.\n' % base,
           'program funit_driver\n',
           '   use funit, only: funit_run_test, funit_finish\n']
    # a module of 57 and a procedure of 63 characters do not fit one line of 132
    out += ['   use %s, only: &\n      %s\n' % (module, name) for name in used]
    out.append('   implicit none\n')
    for t in tests:
        args = ["'%s'" % module, "'%s'" % t, t]  # one per line: names may be 63 chars
        args += ['before=' + before] if before else []
        args += ['after=' + after] if after else []
        out.append('   call funit_run_test(%s)\n' % ', &\n        '.join(args))
    out += ["   call funit_finish('%s')\n" % module, 'end program funit_driver\n']
    return ''.join(out)


def main(argv):
    if len(argv) != 4:
        sys.stderr.write(__doc__.split('\n\n')[1] + '\n')
        return 2
    path, out_module, out_driver = os.path.abspath(argv[1]), argv[2], argv[3]
    try:
        with open(path) as f:
            lines = f.readlines()
        if lines and not lines[-1].endswith('\n'):
            lines[-1] += '\n'
        source, tests, before, after = translate(path, lines)
    except PfError as e:
        sys.stderr.write('%s\n' % e)
        return 1
    module = os.path.splitext(os.path.basename(path))[0]
    with open(out_module, 'w') as f:
        f.write(source)
    with open(out_driver, 'w') as f:
        f.write(driver(path, module, tests, before, after))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
