"""The rockhatch command in Python: the same option table as the C++ program
(carto.parse_command_line), plus the styles written in Python (--script, or a style
script run on its own)."""
import sys
import traceback

from . import carto
from ._rockhatch import RockhatchError, TexError


def fail(error, bar, prog="rockhatch"):
    """Ends the progress bar, writes the error on one line, returns its exit code."""
    bar.finish()
    sys.stderr.write(f"{prog}: {error}\n")
    return getattr(error, "code", 1) if isinstance(error, RockhatchError) else 1


def main(argv=None, style=None):
    """Runs the command; returns its exit code. style: a script module to use instead of
    --script (a style script run on its own passes itself). `update ...`: rockhatch update."""
    argv = sys.argv[1:] if argv is None else list(argv)
    bar = carto.ProgressBar(False)
    update = bool(argv) and argv[0] == "update"
    prog = "rockhatch update" if update else "rockhatch"
    try:
        if update:
            u = carto.parse_update_command_line(argv[1:])
            cl = u.command
        else:
            cl = carto.parse_command_line(argv)
        if cl.help:
            sys.stdout.write(carto.update_help_text() if update else carto.help_text())
            return 0
        if cl.list_styles:
            sys.stdout.write(carto.styles_text())
            return 0
        options = cl.options
        if update:
            options.overwrite = True  # the outputs are the files to update
        chosen = style if style is not None else (cl.script or None)
        if chosen is not None:
            if options.style:
                raise carto.error(2, "--style and --script (or a style script) exclude each other")
            options.style_file = carto.style_file(chosen)
            carto.check_files(options)  # before the script runs: never write onto an input
            options.custom_style = carto.as_style(chosen) if not isinstance(chosen, str) else carto.load_style(chosen)
        bar = carto.ProgressBar(not cl.quiet)
        if update:
            r = carto.update_options(options, bar, reset=u.reset, faces=u.faces)
            bar.finish()
            sys.stderr.write("rockhatch update: %d faces, %d redrawn (%d new), %d removed; features: %d removed, "
                             "%d written, %d unchanged; %.2f s\n" % (r.faces, r.redrawn, r.appeared, r.removed,
                                                                     r.deleted, r.written, r.kept, r.seconds))
            return 0
        stats = carto.run_options(options, bar)
        bar.finish()
        if not cl.quiet:
            for note in stats.notes:
                sys.stderr.write(f"rockhatch: note: {note}\n")
        sys.stderr.write("rockhatch: %d faces, %d hatches, %.2f s, working CRS %s\n"
                         % (stats.faces, stats.hatches, stats.seconds, stats.crs))
        return 0
    except (RockhatchError, TexError) as e:
        return fail(e, bar, prog)
    except Exception:  # an error in a style script: its traceback helps its author
        bar.finish()
        traceback.print_exc()
        sys.stderr.write("rockhatch: the style script failed (traceback above)\n")
        return 1
