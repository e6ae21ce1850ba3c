"""Command line interface: ``leadscrew check``.

Errors print one line and exit non-zero; ``--debug`` shows the traceback.
"""

from __future__ import annotations

import argparse
import math
import sys

from . import thread as _thread

__all__ = ["main"]


def _check(args: argparse.Namespace) -> int:
    t = _thread.Thread(args.pitch, args.mean_diameter, args.starts, math.radians(args.flank_angle_deg))
    mu = args.mu
    tan_a = math.tan(t.lead_angle)
    print(f"thread: lead {t.lead * 1e3:.4g} mm, mean diameter {t.mean_diameter * 1e3:.4g} mm, "
          f"lead angle {math.degrees(t.lead_angle):.4f} deg, flank angle {args.flank_angle_deg:g} deg")
    print(f"friction: mu = {mu:g}, mu' = {t.effective_mu(mu):.6g}; "
          f"bounds tan(alpha) = {tan_a:.6g} < mu' < cot(alpha) = {1.0 / tan_a:.6g}")
    print(f"self-locking (holds under pure axial load): {'yes' if _thread.is_self_locking(t, mu) else 'no'}")
    print(f"drivable by a pure torque:                 {'yes' if _thread.is_drivable(t, mu) else 'no'}")
    print(f"efficiency forward {_thread.efficiency(t, mu):.6g}, "
          f"back-driving {_thread.efficiency(t, mu, backdrive=True):.6g}")
    if args.load is not None:
        print(f"torque to raise {args.load:g} N: {_thread.raise_torque(t, mu, args.load):.6g} N*m, "
              f"to lower: {_thread.lower_torque(t, mu, args.load):.6g} N*m")
    return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="leadscrew", description="Lead-screw drive simulator")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    sub = parser.add_subparsers(dest="command", required=True)
    check = sub.add_parser("check", help="closed-form verdicts of a thread "
                           "(default: the thesis's Table 5.1 drive)")
    check.add_argument("--pitch", type=float, default=1e-3, help="pitch [m] (default 1e-3)")
    check.add_argument("--mean-diameter", type=float, default=20e-3, help="mean diameter [m] (default 20e-3)")
    check.add_argument("--starts", type=int, default=1)
    check.add_argument("--flank-angle-deg", type=float, default=0.0, help="included flank angle [deg]")
    check.add_argument("--mu", type=float, default=0.3, help="flank friction coefficient (default 0.3)")
    check.add_argument("--load", type=float, default=None, help="axial load [N] for the torques")
    check.set_defaults(func=_check)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line. Returns the exit code."""
    args = _parser().parse_args(argv)
    try:
        return args.func(args)
    except Exception as error:  # one clear line unless --debug
        if args.debug:
            raise
        print(f"leadscrew: error: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
