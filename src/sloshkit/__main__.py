"""``python -m sloshkit``: the command line."""

from sloshkit.cli import main

if __name__ == "__main__":
    main()
