"""`fickcam sweep --scheduler ADDRESS` with a wrong address ends in seconds with one line."""
import http.server
import socket
import socketserver
import threading
import time
from pathlib import Path

import pytest

from fickcam.cli.main import main

SWEEP = Path(__file__).resolve().parents[1] / "configs" / "sweep_singh2017_climate.yaml"
SECONDS = 15  # probe timeout 3 s, plus imports: far below dask's own 20 s or a hang


@pytest.fixture
def server():
    """Start a TCP server of the given handler class in a thread; yield its port."""
    started = []

    def start(handler):
        srv = socketserver.ThreadingTCPServer(("127.0.0.1", 0), handler)
        srv.daemon_threads = True
        threading.Thread(target=srv.serve_forever, daemon=True).start()
        started.append(srv)
        return srv.server_address[1]

    yield start
    for srv in started:
        srv.shutdown()
        srv.server_close()


class Greeter(socketserver.BaseRequestHandler):
    """Another protocol that greets first (as SSH or SMTP do)."""

    def handle(self):
        self.request.sendall(b"SSH-2.0-OpenSSH_9.6\r\n")
        time.sleep(0.5)


def closed_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def sweep_with(address, tmp_path, capsys):
    started = time.perf_counter()
    code = main(["sweep", str(SWEEP), "--scheduler", address, "-o", str(tmp_path / "out.h5"),
                 "--quiet"])
    elapsed = time.perf_counter() - started
    err = capsys.readouterr().err.strip().splitlines()
    assert elapsed < SECONDS, f"{address}: took {elapsed:.1f} s"
    assert len(err) == 1 and "Traceback" not in err[0] and "internal error" not in err[0], err
    return code, err[0]


@pytest.mark.slow
def test_an_http_server_is_refused_in_seconds(server, tmp_path, capsys):
    """It stays silent: the probe's own timeout (3 s) ends the wait."""
    port = server(http.server.SimpleHTTPRequestHandler)
    code, line = sweep_with(f"tcp://127.0.0.1:{port}", tmp_path, capsys)
    assert code == 2 and "not a dask scheduler" in line
    code, line = sweep_with(f"http://127.0.0.1:{port}", tmp_path, capsys)
    assert code == 2 and "tcp://HOST:8786" in line


def test_a_server_of_another_protocol_is_refused(server, tmp_path, capsys):
    code, line = sweep_with(f"127.0.0.1:{server(Greeter)}", tmp_path, capsys)
    assert code == 2 and "not a dask scheduler" in line


def test_a_closed_port_is_an_unreachable_scheduler(tmp_path, capsys):
    code, line = sweep_with(f"tcp://127.0.0.1:{closed_port()}", tmp_path, capsys)
    assert code == 1 and line.startswith("fickcam: error: no dask scheduler at")


@pytest.mark.parametrize("address", ["garbage address", "tcp://127.0.0.1", "tcp://:8786",
                                      "nosuch://host:8786"])
def test_a_malformed_address_is_bad_input(address, tmp_path, capsys):
    code, line = sweep_with(address, tmp_path, capsys)
    assert code == 2 and line.startswith(f"fickcam: error: --scheduler {address}")
