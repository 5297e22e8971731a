#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Opens URL in headless Chromium in real time (a virtual time budget would
# stop the page's clock) and prints the page's title once it starts with one
# of PREFIXES (comma-separated), read over the debugging port; then closes
# the browser. Exit 1, printing nothing, after TIMEOUT seconds.
#   chromium-title.py URL PREFIXES TIMEOUT PROFILE-DIR
import json
import os
import re
import subprocess
import sys
import tempfile
import time
import urllib.request

url, prefixes, timeout, profile = sys.argv[1], tuple(sys.argv[2].split(',')), float(sys.argv[3]), sys.argv[4]
log = tempfile.NamedTemporaryFile(prefix='chromium-', suffix='.log', delete=False)
browser = subprocess.Popen(['chromium', '--headless=new', '--no-sandbox', '--use-angle=swiftshader',
                            '--enable-unsafe-swiftshader', '--remote-debugging-port=0', f'--user-data-dir={profile}',
                            url], stdout=subprocess.DEVNULL, stderr=log)
try:
    deadline = time.time() + timeout
    while time.time() < deadline:
        m = re.search(r'DevTools listening on ws://127.0.0.1:(\d+)', open(log.name).read())
        if m:
            try:
                pages = json.load(urllib.request.urlopen(f'http://127.0.0.1:{m.group(1)}/json/list', timeout=2))
                titles = [p['title'] for p in pages if p.get('title', '').startswith(prefixes)]
                if titles:
                    print(titles[0])
                    sys.exit(0)
            except OSError:
                pass
        time.sleep(0.5)
    sys.exit(1)
finally:
    browser.kill()
    browser.wait()
    os.unlink(log.name)
