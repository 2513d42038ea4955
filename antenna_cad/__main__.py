"""Console entry of ``make-lens`` (and ``python -m antenna_cad``): Ctrl-C handling first, then the CLI."""

import signal

from antenna_cad.interrupt import hold_if_stopping, stop_on_interrupt


def main() -> None:
    stop_on_interrupt()
    from antenna_cad.cli import main as cli_main
    try:
        cli_main()
    finally:
        hold_if_stopping()
        # the work is done: Python resets handled signals to SIG_DFL while it shuts down, so a Ctrl-C
        # landing then would end an already finished run as "killed by SIGINT" (-2) instead of 0
        signal.signal(signal.SIGINT, signal.SIG_IGN)


if __name__ == "__main__":
    main()
