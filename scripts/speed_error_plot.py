"""What the speed-against-error plots share: gnuplot's log-log PNG set-up and the arrows from one
point of a scene to another (scripts/plot-speed-error.py, scripts/plot-old-new.py)."""


def gnuplot_header(out, xlabel, title, arrows):
    """The script's lines before its `plot`: `arrows` are (x0, y0, x1, y1) from point to point."""
    arrow_cmds = "\n".join(
        f"set arrow from {x0},{y0} to {x1},{y1} lc rgb '#888888' dt 2" for x0, y0, x1, y1 in arrows)
    return f"""
set terminal pngcairo size 1000,650 font ',10'
set output '{out}'
set logscale xy
set format y '10^{{%L}}'
set xlabel '{xlabel}'
set ylabel 'position error in motion vs reference (% of its largest displacement)'
set title '{title}'
set grid
set key top right
{arrow_cmds}
"""
