"""Whether the browser tests can run here: Debian's chromium, chromium-driver and python3-selenium."""

import shutil
import sys
from pathlib import Path

# CTest's code for a skipped test (SKIP_RETURN_CODE in tests/report/CMakeLists.txt).
SKIP = 77


def missing_browser():
    """The first missing piece, named as the package that brings it; None when all are here."""
    if not shutil.which("chromedriver") and not Path("/usr/bin/chromedriver").exists():
        return "chromedriver (Debian package chromium-driver)"
    if not Path("/usr/bin/chromium").exists() and not shutil.which("chromium"):
        return "chromium"
    try:
        import viewer_driver  # noqa: F401  (imports selenium)
    except ImportError:
        return "selenium (Debian package python3-selenium)"
    return None


def skip_unless_browser():
    """Exits with SKIP and a message when the browser tests cannot run."""
    missing = missing_browser()
    if missing:
        print("skipped: %s is not installed (./bootstrap deps installs it)" % missing)
        sys.exit(SKIP)
