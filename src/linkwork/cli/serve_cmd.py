"""`linkwork serve`: the browser workbench on a local server (see `linkwork.web`).

It binds 127.0.0.1 unless another host is named together with `--expose`, which prints a
warning: the workbench has no accounts, so anyone who reaches the port may use it."""

from __future__ import annotations

import socket
import webbrowser
from pathlib import Path
from typing import Optional
from urllib.parse import urlencode

import typer

from ..errors import InputError
from ..io.library import LIBRARY_PREFIX, library_names
from .common import print_message, user_errors

LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1")


def _free_port(host: str, port: int) -> int:
    """`port` if it can be bound on `host` (any free port for 0), else a clear error."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        try:
            s.bind((host, port))
        except OSError as exc:
            raise InputError(f"cannot listen on {host}:{port} ({exc.strerror or exc}); give "
                             "another --port (0 takes a free one)") from None
        return s.getsockname()[1]


def _query(mechanism: Optional[str], workdir: Optional[Path]) -> tuple[str, Optional[Path]]:
    """The page's query naming `mechanism`, and the working folder (a file's own folder when
    none is given)."""
    if not mechanism:
        return "", workdir
    if mechanism.startswith(LIBRARY_PREFIX):
        name = mechanism[len(LIBRARY_PREFIX):]
        if name not in library_names():
            raise InputError(f"the library has no mechanism '{name}'; `linkwork library` lists them")
        return "?" + urlencode({"library": name}), workdir
    path = Path(mechanism).resolve()
    if not path.is_file():
        raise InputError(f"no mechanism file '{mechanism}' (give a path, or library:NAME)")
    root = (workdir or path.parent).resolve()
    if not path.is_relative_to(root):
        raise InputError(f"'{mechanism}' is not inside the working folder {root}")
    return "?" + urlencode({"file": path.relative_to(root).as_posix()}), root


def server_options() -> dict:
    """uvicorn's settings for `linkwork serve` besides host and port. A WebSocket message is
    limited to the size of a request body (`web.app.MAX_BODY`), as HTTP's are: a larger one
    closes the socket with code 1009 (message too big) before it is read whole, where
    uvicorn's default would take messages of 16 MB into memory."""
    from ..web.app import MAX_BODY
    return {"log_level": "warning", "ws_max_size": MAX_BODY}


def register(app: typer.Typer) -> None:
    @app.command()
    def serve(
        mechanism: Optional[str] = typer.Argument(None, help="open this mechanism: library:NAME or a file (inside the working folder)"),
        port: int = typer.Option(8765, "--port", help="the port to listen on (0: any free port)"),
        host: str = typer.Option("127.0.0.1", "--host", help="the address to listen on; anything but this computer needs --expose"),
        expose: bool = typer.Option(False, "--expose", help="allow --host to be an address other computers reach (prints a warning)"),
        workdir: Optional[Path] = typer.Option(None, "--workdir", help="the folder whose mechanism files the workbench may open (default: the folder of MECHANISM, else none)"),
        open_browser: bool = typer.Option(False, "--open", help="open the page in the web browser"),
    ) -> None:
        """The browser workbench: see, animate and drag a mechanism, with its poles, centrodes
        and curvature layers, on a local server."""
        with user_errors():
            if not 0 <= port <= 65535:
                raise InputError(f"--port {port}: give 0 to 65535")
            if host not in LOCAL_HOSTS and not expose:
                raise InputError(f"--host {host} lets other computers reach the workbench; "
                                 "add --expose to mean it")
            if workdir is not None and not workdir.is_dir():
                raise InputError(f"--workdir {workdir}: no such folder")
            query, root = _query(mechanism, workdir)
            port = _free_port(host, port)
            import uvicorn  # the server and the engine load only for this command

            from ..web import create_app
            from ..web.app import STATIC
            if host not in LOCAL_HOSTS:
                print_message("warning", f"the workbench listens on {host}: anyone who reaches "
                                         f"this address can use it and read the mechanism files "
                                         f"of {root or 'the library'}")
            if not (STATIC / "app.js").is_file():
                print_message("warning", "the page is not built (web/): `./run linkwork serve` "
                                         "builds it; the API works without it")
            shown = f"[{host}]" if ":" in host else host
            url = f"http://{shown}:{port}/{query}"
            typer.echo(f"linkwork workbench: {url}  (Ctrl-C stops it)")
            if root is not None:
                typer.echo(f"working folder: {root}")
            if open_browser:
                webbrowser.open(url)
            # on this computer, only requests addressed to it by its own names (DNS rebinding)
            hosts = LOCAL_HOSTS if host in LOCAL_HOSTS else None
            uvicorn.run(create_app(root, compiled=True, hosts=hosts), host=host, port=port,
                        **server_options())
