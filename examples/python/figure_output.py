"""Where the examples' figures go: shown on a display, else (or when an
output is named) written to a PNG with matplotlib's Agg backend."""
import os


def pyplot(output):
    """matplotlib.pyplot, with the Agg backend when output is given or there is no display."""
    import matplotlib
    if output or not os.environ.get("DISPLAY"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def show_or_save(figure, output, default_name):
    """Writes the figure to output (default_name without a display), else shows it."""
    import matplotlib.pyplot as plt
    figure.tight_layout()
    output = output or (None if os.environ.get("DISPLAY") else default_name)
    if output:
        figure.savefig(output, dpi=100)
        print("wrote", output)
    else:
        plt.show()
