"""Minimal SVG line plots on log or linear axes (Python standard library only).

Used by bench/run_all to draw the figures of bench/RESULTS.md:

    p = Plot("Time against N", "faces N", "CPU time (s)", logx=True, logy=True)
    p.series("Franklin exact", [(1e3, 0.2), (1e4, 2.1)])
    p.hline(1.5, "exact engine")
    open("out.svg", "w").write(p.svg())
"""

import math
from xml.sax.saxutils import escape

# Colour-blind-safe palette (Okabe & Ito), then greys.
PALETTE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
           "#999999", "#666666"]
MARKERS = ["circle", "square", "diamond", "triangle", "circle", "square", "diamond", "triangle", "circle", "square"]


def _fmt(v):
    """Tick label: 10^k as 1e3, or a short decimal."""
    if v == 0:
        return "0"
    e = math.log10(abs(v))
    if abs(e - round(e)) < 1e-9 and (abs(e) >= 3):
        return f"1e{int(round(e))}"
    if abs(v) >= 1000 or abs(v) < 0.01:
        return f"{v:.0e}".replace("e+0", "e").replace("e-0", "e-")
    s = f"{v:.3g}"
    return s


class Plot:
    def __init__(self, title, xlabel, ylabel, logx=True, logy=True, width=820, height=440):
        self.title, self.xlabel, self.ylabel = title, xlabel, ylabel
        self.logx, self.logy = logx, logy
        self.w, self.h = width, height
        self.left, self.right, self.top, self.bottom = 78, 290, 40, 56
        self._series = []   # (label, [(x, y)], dashed, labels per point)
        self._hlines = []   # (y, label)
        self._notes = []

    def series(self, label, points, dashed=False, point_labels=None):
        pts = [(x, y) for x, y in points if x is not None and y is not None and self._ok(x, y)]
        if pts:
            self._series.append((label, pts, dashed, point_labels))

    def hline(self, y, label):
        if y is not None and (not self.logy or y > 0):
            self._hlines.append((y, label))

    def note(self, text):
        self._notes.append(text)

    def _ok(self, x, y):
        return (not self.logx or x > 0) and (not self.logy or y > 0)

    def _range(self, values, log):
        lo, hi = min(values), max(values)
        if log:
            lo, hi = math.floor(math.log10(lo) + 1e-9), math.ceil(math.log10(hi) - 1e-9)
            if hi <= lo:
                hi = lo + 1
            return lo, hi
        if hi == lo:
            hi = lo + 1
        pad = 0.05 * (hi - lo)
        lo2 = 0 if lo >= 0 and lo - pad < 0 else lo - pad
        return lo2, hi + pad

    def svg(self):
        xs = [x for _, pts, _, _ in self._series for x, _ in pts]
        ys = [y for _, pts, _, _ in self._series for _, y in pts] + [y for y, _ in self._hlines]
        if not xs:
            xs, ys = [1, 10], [1, 10]
        x0, x1 = self._range(xs, self.logx)
        y0, y1 = self._range(ys, self.logy)
        pw = self.w - self.left - self.right
        ph = self.h - self.top - self.bottom

        def sx(x):
            v = math.log10(x) if self.logx else x
            return self.left + (v - x0) / (x1 - x0) * pw

        def sy(y):
            v = math.log10(y) if self.logy else y
            return self.top + ph - (v - y0) / (y1 - y0) * ph

        out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.w}" height="{self.h}" '
               f'viewBox="0 0 {self.w} {self.h}" font-family="sans-serif" font-size="12">',
               f'<rect width="{self.w}" height="{self.h}" fill="white"/>',
               f'<text x="{self.left + pw / 2:.1f}" y="22" text-anchor="middle" font-size="15" '
               f'font-weight="bold">{escape(self.title)}</text>']
        # Grid and ticks.
        def ticks(lo, hi, log):
            if log:
                major = [10 ** k for k in range(int(lo), int(hi) + 1)]
                minor = [m * 10 ** k for k in range(int(lo), int(hi)) for m in range(2, 10)]
                return major, minor
            step = 10 ** math.floor(math.log10((hi - lo) / 5))
            for m in (1, 2, 5, 10):
                if (hi - lo) / (step * m) <= 7:
                    step *= m
                    break
            first = math.ceil(lo / step) * step
            major = []
            v = first
            while v <= hi + 1e-12:
                major.append(round(v, 12))
                v += step
            return major, []
        xmaj, xmin = ticks(x0, x1, self.logx)
        ymaj, ymin = ticks(y0, y1, self.logy)
        for v in xmin:
            out.append(f'<line x1="{sx(v):.1f}" y1="{self.top}" x2="{sx(v):.1f}" y2="{self.top + ph}" '
                       f'stroke="#eee"/>')
        for v in ymin:
            out.append(f'<line x1="{self.left}" y1="{sy(v):.1f}" x2="{self.left + pw}" y2="{sy(v):.1f}" '
                       f'stroke="#eee"/>')
        for v in xmaj:
            out.append(f'<line x1="{sx(v):.1f}" y1="{self.top}" x2="{sx(v):.1f}" y2="{self.top + ph}" '
                       f'stroke="#ccc"/>')
            out.append(f'<text x="{sx(v):.1f}" y="{self.top + ph + 16}" text-anchor="middle">{_fmt(v)}</text>')
        for v in ymaj:
            out.append(f'<line x1="{self.left}" y1="{sy(v):.1f}" x2="{self.left + pw}" y2="{sy(v):.1f}" '
                       f'stroke="#ccc"/>')
            out.append(f'<text x="{self.left - 6}" y="{sy(v) + 4:.1f}" text-anchor="end">{_fmt(v)}</text>')
        out.append(f'<rect x="{self.left}" y="{self.top}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>')
        out.append(f'<text x="{self.left + pw / 2:.1f}" y="{self.h - 14}" text-anchor="middle">'
                   f'{escape(self.xlabel)}</text>')
        out.append(f'<text x="16" y="{self.top + ph / 2:.1f}" text-anchor="middle" '
                   f'transform="rotate(-90 16 {self.top + ph / 2:.1f})">{escape(self.ylabel)}</text>')
        # Horizontal reference lines.
        legend = []
        for k, (y, label) in enumerate(self._hlines):
            colour = "#444"
            out.append(f'<line x1="{self.left}" y1="{sy(y):.1f}" x2="{self.left + pw}" y2="{sy(y):.1f}" '
                       f'stroke="{colour}" stroke-width="1.5" stroke-dasharray="2,3"/>')
            out.append(f'<text x="{self.left + 4}" y="{sy(y) - 4:.1f}" fill="{colour}" font-size="11">'
                       f'{escape(label)}</text>')
        # Series.
        for k, (label, pts, dashed, plabels) in enumerate(self._series):
            colour = PALETTE[k % len(PALETTE)]
            path = " ".join(f'{"M" if i == 0 else "L"}{sx(x):.1f},{sy(y):.1f}' for i, (x, y) in enumerate(pts))
            dash = ' stroke-dasharray="6,4"' if dashed else ""
            out.append(f'<path d="{path}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>')
            for i, (x, y) in enumerate(pts):
                out.append(_marker(MARKERS[k % len(MARKERS)], sx(x), sy(y), colour))
                if plabels and i < len(plabels) and plabels[i]:
                    out.append(f'<text x="{sx(x) + 5:.1f}" y="{sy(y) - 5:.1f}" font-size="9" fill="{colour}">'
                               f'{escape(str(plabels[i]))}</text>')
            legend.append((label, colour, MARKERS[k % len(MARKERS)], dashed))
        # Legend, right of the plot.
        lx = self.left + pw + 14
        for k, (label, colour, marker, dashed) in enumerate(legend):
            y = self.top + 10 + 20 * k
            dash = ' stroke-dasharray="6,4"' if dashed else ""
            out.append(f'<line x1="{lx}" y1="{y}" x2="{lx + 24}" y2="{y}" stroke="{colour}" stroke-width="2"{dash}/>')
            out.append(_marker(marker, lx + 12, y, colour))
            out.append(f'<text x="{lx + 30}" y="{y + 4}">{escape(label)}</text>')
        for k, text in enumerate(self._notes):
            y = self.top + 10 + 20 * (len(legend) + k) + 10
            out.append(f'<text x="{lx}" y="{y}" font-size="10" fill="#555">{escape(text)}</text>')
        out.append("</svg>")
        return "\n".join(out) + "\n"


def _marker(kind, x, y, colour, r=3.5):
    if kind == "square":
        return f'<rect x="{x - r:.1f}" y="{y - r:.1f}" width="{2 * r}" height="{2 * r}" fill="{colour}"/>'
    if kind == "diamond":
        return (f'<path d="M{x:.1f},{y - r - 1:.1f} L{x + r + 1:.1f},{y:.1f} L{x:.1f},{y + r + 1:.1f} '
                f'L{x - r - 1:.1f},{y:.1f} Z" fill="{colour}"/>')
    if kind == "triangle":
        return (f'<path d="M{x:.1f},{y - r - 1:.1f} L{x + r + 1:.1f},{y + r:.1f} L{x - r - 1:.1f},{y + r:.1f} Z" '
                f'fill="{colour}"/>')
    return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r}" fill="{colour}"/>'
