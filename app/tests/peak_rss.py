#!/usr/bin/env python3
"""Runs a command as it is (its stdin, stdout, stderr and exit status passed through) and writes the
largest resident set it reached, in KiB, to a file: what a test of --max-memory checks against the
limit (app/tests/expect_outcome.cmake's MAX_RSS_MB). Only the standard library (resource.getrusage).

    peak_rss.py KIB_FILE COMMAND [ARG ...]

A command killed by a signal exits with 128 + the signal, as a shell reports it.
"""
import resource
import subprocess
import sys


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: peak_rss.py KIB_FILE COMMAND [ARG ...]")
    status = subprocess.call(sys.argv[2:])
    with open(sys.argv[1], "w") as out:
        out.write("%d\n" % resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
    sys.exit(128 - status if status < 0 else status)


if __name__ == "__main__":
    main()
