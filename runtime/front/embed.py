#!/usr/bin/env python3
"""embed.py IN OUT NAME: IN as NAME, an array of its lines (C strings, then a null pointer), in the header OUT."""
import sys

src, out, name = sys.argv[1:4]
with open(src, encoding='utf-8') as f:
    text = f.read()
lines = ['/* %s, built in by embed.py: do not edit */' % src.split('/')[-1],
         'static const char *const %s[] = {' % name]
for line in text.splitlines(True):
    esc = line.replace('\\', '\\\\').replace('"', '\\"').replace('\n', '\\n')
    esc = esc.replace('??', '?\\?')  # no trigraphs
    lines.append('    "%s",' % esc)  # one literal a line: none too long for C
lines.append('    0};')
with open(out, 'w', encoding='utf-8') as f:
    f.write('\n'.join(lines) + '\n')
