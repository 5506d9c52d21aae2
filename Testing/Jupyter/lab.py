"""A JupyterLab server on the loopback address and a headless Chromium driving it, each started
for one test and stopped afterwards, whatever happens: the server runs in a process group of
its own (killed as a group, with the kernels and the trame servers it started), Chromium under
Selenium's chromedriver (quit, then its process group killed)."""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path
from typing import Callable, Iterator

CHROMIUM = os.environ.get("SPT_CHROMIUM", "/usr/bin/chromium")
CHROMEDRIVER = os.environ.get("SPT_CHROMEDRIVER", "/usr/bin/chromedriver")


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _stop_group(process: subprocess.Popen, grace: float = 10.0) -> None:
    """SIGTERM to the process group, SIGKILL to what is left of it after ``grace`` seconds."""
    if process.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(grace)
        except subprocess.TimeoutExpired:
            pass
    with contextlib.suppress(ProcessLookupError):
        os.killpg(process.pid, signal.SIGKILL)
    process.wait()


@contextlib.contextmanager
def jupyter_lab(root: Path, startup: float = 180.0) -> Iterator[Callable[[str], str]]:
    """JupyterLab serving ``root``, with its own runtime, configuration and data folders under
    ``root/.jupyter-*`` (nothing of the user's), a random token, on 127.0.0.1 and a free port;
    ``window.jupyterapp`` exposed to the page. Yields ``url(path)``, a page of it with the
    token, once /api answers."""
    home = root / ".jupyter-home"
    environment = {**os.environ, "JUPYTER_RUNTIME_DIR": str(home / "runtime"),
                   "JUPYTER_CONFIG_DIR": str(home / "config"),
                   "JUPYTER_DATA_DIR": str(home / "data"), "IPYTHONDIR": str(home / "ipython"),
                   "JUPYTER_PLATFORM_DIRS": "1"}
    port, token = free_port(), secrets.token_hex(16)
    log = root / "jupyter-lab.log"
    command = [sys.executable, "-m", "jupyter", "lab", "--no-browser", "--allow-root",
               "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={port}",
               "--ServerApp.port_retries=0", f"--IdentityProvider.token={token}",
               f"--ServerApp.root_dir={root}", "--LabApp.expose_app_in_browser=True",
               "--LabApp.news_url=", "--LabApp.check_for_updates_class="
               "jupyterlab.NeverCheckForUpdate"]
    with open(log, "wb") as output:
        process = subprocess.Popen(command, cwd=root, env=environment, stdout=output,
                                   stderr=subprocess.STDOUT, start_new_session=True)

    def url(path: str) -> str:
        return f"http://127.0.0.1:{port}/{path}?token={token}"

    try:
        deadline = time.monotonic() + startup
        while True:
            if process.poll() is not None:
                raise RuntimeError(f"jupyter lab exited ({process.returncode}):\n"
                                   + log.read_text(errors="replace")[-4000:])
            try:
                with urllib.request.urlopen(url("api"), timeout=5) as answer:
                    json.load(answer)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise RuntimeError(f"jupyter lab did not answer on port {port} in "
                                       f"{startup:.0f} s:\n"
                                       + log.read_text(errors="replace")[-4000:])
                time.sleep(0.5)
        yield url
    finally:
        _stop_group(process)


@contextlib.contextmanager
def chromium(width: int = 1200, height: int = 1000):
    """A headless Chromium (Debian's) under Selenium, one CSS pixel to one pixel."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu",
                     "--disable-dev-shm-usage", "--force-device-scale-factor=1",
                     f"--window-size={width},{height}"):
        options.add_argument(argument)
    service = Service(CHROMEDRIVER, popen_kw={"start_new_session": True})
    driver = webdriver.Chrome(service=service, options=options)
    try:
        driver.set_page_load_timeout(120)
        driver.set_script_timeout(600)
        yield driver
    finally:
        with contextlib.suppress(Exception):
            driver.quit()
        if service.process is not None:
            _stop_group(service.process, grace=5.0)


def notebook(path: Path, cells) -> Path:
    """A notebook of code ``cells`` (strings), for Python 3, at ``path``."""
    document = {"cells": [{"cell_type": "code", "metadata": {}, "source": cell, "outputs": [],
                           "execution_count": None} for cell in cells],
                "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3",
                                            "language": "python"}},
                "nbformat": 4, "nbformat_minor": 5}
    path.write_text(json.dumps(document, indent=1))
    return path
