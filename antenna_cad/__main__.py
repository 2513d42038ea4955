"""Console entry of ``make-lens`` (and ``python -m antenna_cad``): Ctrl-C handling first, then the CLI."""

from antenna_cad.interrupt import hold_if_stopping, stop_on_interrupt


def main() -> None:
    stop_on_interrupt()
    from antenna_cad.cli import main as cli_main
    try:
        cli_main()
    finally:
        hold_if_stopping()


if __name__ == "__main__":
    main()
