#!/usr/bin/env python3
"""Fail unless doc/parameters.md lists exactly what viscofilm --print-parameters
prints (usage: check_parameters_doc.py VISCOFILM DOC)."""
import subprocess
import sys

viscofilm, doc = sys.argv[1:3]
text = open(doc).read()
begin = text.index("<!-- BEGIN print-parameters -->\n```\n") + len(
    "<!-- BEGIN print-parameters -->\n```\n")
end = text.index("```\n<!-- END print-parameters -->")
printed = subprocess.run([viscofilm, "--print-parameters"], capture_output=True,
                         text=True, check=True).stdout
if text[begin:end] != printed:
    print("FAILED: %s is out of date; regenerate its block with "
          "'viscofilm --print-parameters'" % doc)
    sys.exit(1)
print("PASSED")
