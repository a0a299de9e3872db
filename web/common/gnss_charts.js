// SPDX-License-Identifier: Apache-2.0
// Charts shared by the live status page and the HTML report (docs/status.md).
// Everything is drawn by Chart.js 3 (Debian libjs-chart.js); the sky plot is a
// scatter chart in polar projection (radius = 90 deg - elevation) whose rings
// and spokes are line datasets, so the library scales, draws and hit-tests all.
'use strict';

const GnssCharts = (() => {
  // One colour per satellite state (daemon/sat_state.hpp), u-center-like.
  const stateColors = {
    used: '#1f9d3a',
    nlos: '#e08a00',
    excluded: '#c0392b',
    tracked: '#2f6fd6',
    searching: '#9aa3ad',
    blocked: '#5b2c83',
    below_mask: '#d0d4d9',
  };
  const stateLabels = {
    used: 'used',
    nlos: 'NLOS (reflected only)',
    excluded: 'excluded by fault detection',
    tracked: 'tracked, not used',
    searching: 'searching (weak)',
    blocked: 'blocked',
    below_mask: 'below mask',
  };
  const states = Object.keys(stateColors);
  const deg = Math.PI / 180;

  /** Sky-plot coordinates of azimuth/elevation in degrees: x east, y north. */
  function skyXY(azDeg, elDeg) {
    const r = (90 - Math.max(-5, Math.min(90, elDeg))) / 90;
    return { x: r * Math.sin(azDeg * deg), y: r * Math.cos(azDeg * deg) };
  }

  function ring(elDeg, n = 120) {
    const pts = [];
    for (let k = 0; k <= n; k++) pts.push(skyXY((360 * k) / n, elDeg));
    return pts;
  }

  function gridDatasets(maskDeg) {
    const grid = { type: 'line', showLine: true, pointRadius: 0, borderWidth: 1, borderColor: '#c8ccd2',
                   fill: false, order: 100, gridLine: true };
    const sets = [0, 30, 60].map((el) => ({ ...grid, label: `el ${el}`, data: ring(el) }));
    sets.push({ ...grid, label: 'N-S', data: [skyXY(0, 0), skyXY(180, 0)] });
    sets.push({ ...grid, label: 'E-W', data: [skyXY(90, 0), skyXY(270, 0)] });
    if (maskDeg > 0) {
      sets.push({ ...grid, label: `mask ${maskDeg.toFixed(0)}°`, data: ring(maskDeg), borderColor: '#c0392b',
                  borderDash: [6, 4], borderWidth: 1.5, gridLine: false, mask: true });
    }
    return sets;
  }

  // Compass letters and elevation ring labels; PRN numbers beside live points.
  const skyLabels = {
    id: 'skyLabels',
    afterDatasetsDraw(chart) {
      const { ctx, scales } = chart;
      const px = (p) => ({ x: scales.x.getPixelForValue(p.x), y: scales.y.getPixelForValue(p.y) });
      ctx.save();
      ctx.font = '12px sans-serif';
      ctx.fillStyle = '#555';
      ctx.textAlign = 'center';
      ctx.textBaseline = 'middle';
      for (const [t, az] of [['N', 0], ['E', 90], ['S', 180], ['W', 270]]) {
        const p = px(skyXY(az, -7));
        ctx.fillText(t, p.x, p.y);
      }
      ctx.font = '10px sans-serif';
      ctx.fillStyle = '#999';
      for (const el of [30, 60]) {
        const p = px(skyXY(45, el));
        ctx.fillText(`${el}°`, p.x + 10, p.y);
      }
      if (chart.options.plugins.skyLabels && chart.options.plugins.skyLabels.prn) {
        ctx.font = 'bold 11px sans-serif';
        ctx.fillStyle = '#222';
        ctx.textAlign = 'left';
        chart.data.datasets.forEach((ds, i) => {
          if (ds.gridLine || ds.mask || !chart.isDatasetVisible(i)) return;
          const meta = chart.getDatasetMeta(i);
          meta.data.forEach((el, k) => {
            const p = ds.data[k];
            const name = p && (p.sat !== undefined ? p.sat : p.prn);
            if (name !== undefined) ctx.fillText(String(name), el.x + 8, el.y - 7);
          });
        });
      }
      ctx.restore();
    },
  };

  /**
   * Pads the chart so its plot area is square whatever the legend and tick
   * labels take: equal ranges on x and y then keep circles round.
   */
  const squarePlot = {
    id: 'squarePlot',
    afterLayout(chart) {
      // A narrower area can wrap the legend: a few rounds settle it.
      if ((chart.$squaring || 0) >= 4) return;
      const a = chart.chartArea;
      const p = chart.$squarePad || { l: 0, r: 0, t: 0, b: 0 };
      const d = (a.width + p.l + p.r) - (a.height + p.t + p.b);
      const next = d > 0 ? { l: d / 2, r: d / 2, t: 0, b: 0 } : { l: 0, r: 0, t: -d / 2, b: -d / 2 };
      if (Math.abs(a.width - a.height) < 1 || Math.abs(next.l - p.l) + Math.abs(next.t - p.t) < 0.5) return;
      chart.$squarePad = next;
      chart.options.layout.padding = { left: next.l, right: next.r, top: next.t, bottom: next.b };
      chart.$squaring = (chart.$squaring || 0) + 1;
      try {
        chart.update('none');
      } finally {
        chart.$squaring -= 1;
      }
    },
  };

  /** A sky plot on canvas; opts.prnLabels: write PRN numbers beside points. */
  function skyChart(canvas, opts = {}) {
    return new Chart(canvas, {
      type: 'scatter',
      data: { datasets: [] },
      options: {
        animation: false,
        aspectRatio: 1,
        parsing: false,
        scales: {
          x: { min: -1.12, max: 1.12, display: false },
          y: { min: -1.12, max: 1.12, display: false },
        },
        plugins: {
          skyLabels: { prn: !!opts.prnLabels },
          legend: { position: 'bottom', labels: { filter: (item, data) => {
            const ds = data.datasets[item.datasetIndex];
            return !ds.gridLine;
          } } },
          tooltip: { callbacks: { label: (c) => {
            const p = c.raw;
            if (p.prn === undefined) return c.dataset.label;
            return `${p.sat !== undefined ? p.sat : 'PRN ' + p.prn}: az ${p.az.toFixed(0)}°, el ${p.el.toFixed(0)}°` +
              (p.cn0 ? `, ${p.cn0.toFixed(1)} dB-Hz` : '') + ` (${c.dataset.label})`;
          } } },
        },
      },
      plugins: [skyLabels, squarePlot],
    });
  }

  /** One dataset per state of the points {prn, az, el, cn0, state, used}. */
  // Rarer, more telling states are drawn over the common ones.
  const drawOrder = { excluded: 1, nlos: 2, blocked: 3, searching: 4, tracked: 5, used: 6, below_mask: 7 };

  /** alpha < 1: translucent points, so overlapping states of a moving run blend. */
  function rgba(hex, alpha) {
    if (alpha >= 1) return hex;
    const n = parseInt(hex.slice(1), 16);
    return `rgba(${(n >> 16) & 255},${(n >> 8) & 255},${n & 255},${alpha})`;
  }

  function skyDatasets(points, maskDeg, pointRadius, alpha = 1) {
    const sets = gridDatasets(maskDeg);
    for (const s of states) {
      const pts = points.filter((p) => p.state === s).map((p) => ({ ...skyXY(p.az, p.el), ...p }));
      if (!pts.length) continue;
      sets.push({
        label: stateLabels[s],
        data: pts,
        backgroundColor: pts.map((p) => (p.used === false && s === 'nlos' && alpha >= 1 ? '#ffffff' : rgba(stateColors[s], alpha))),
        borderColor: rgba(stateColors[s], alpha),
        borderWidth: alpha >= 1 ? 2 : 0,
        pointRadius,
        pointHoverRadius: pointRadius + 2,
        order: drawOrder[s],
      });
    }
    return sets;
  }

  /** C/N0 bars per PRN coloured by state, with the tracking thresholds. */
  function cn0Chart(canvas) {
    return new Chart(canvas, {
      type: 'bar',
      data: { labels: [], datasets: [] },
      options: {
        animation: false,
        maintainAspectRatio: false,
        scales: {
          y: { min: 0, max: 55, title: { display: true, text: 'C/N0 (dB-Hz)' } },
          x: { title: { display: true, text: 'PRN' } },
        },
        plugins: { legend: { position: 'bottom' } },
      },
    });
  }

  function cn0Data(sats, acquireDbhz, loseDbhz) {
    const shown = sats.filter((s) => s.state !== 'below_mask');
    const labels = shown.map((s) => String(s.sat !== undefined ? s.sat : s.prn));
    const flat = (v) => labels.map(() => v);
    return {
      labels,
      datasets: [
        { type: 'bar', label: 'C/N0', data: shown.map((s) => s.cn0_dbhz),
          backgroundColor: shown.map((s) => stateColors[s.state] || '#888'), order: 2 },
        { type: 'line', label: `acquire ${acquireDbhz} dB-Hz`, data: flat(acquireDbhz), borderColor: '#1f9d3a',
          borderDash: [6, 3], borderWidth: 1.5, pointRadius: 0, order: 1 },
        { type: 'line', label: `lose lock ${loseDbhz} dB-Hz`, data: flat(loseDbhz), borderColor: '#c0392b',
          borderDash: [2, 3], borderWidth: 1.5, pointRadius: 0, order: 1 },
      ],
    };
  }

  /** A line chart over x values (s) with the given series [{label, color, data}]. */
  function timeChart(canvas, yTitle, xTitle = 'time (s)') {
    return new Chart(canvas, {
      type: 'line',
      data: { datasets: [] },
      options: {
        animation: false,
        maintainAspectRatio: false,
        parsing: false,
        normalized: true,
        spanGaps: false,
        elements: { point: { radius: 0 }, line: { borderWidth: 1.5 } },
        scales: {
          x: { type: 'linear', title: { display: true, text: xTitle } },
          y: { title: { display: true, text: yTitle } },
        },
        plugins: { legend: { position: 'bottom' } },
        interaction: { mode: 'nearest', axis: 'x', intersect: false },
      },
    });
  }

  function series(label, color, xs, ys, extra = {}) {
    const data = [];
    for (let i = 0; i < xs.length; i++) data.push({ x: xs[i], y: ys[i] === null ? NaN : ys[i] });
    return { label, data, borderColor: color, backgroundColor: color, ...extra };
  }

  function circle(r, n = 90) {
    const pts = [];
    for (let k = 0; k <= n; k++) pts.push({ x: r * Math.cos((2 * Math.PI * k) / n), y: r * Math.sin((2 * Math.PI * k) / n) });
    return pts;
  }

  /** Horizontal error scatter (east, north) with CEP circles, square axes. */
  function scatterChart(canvas) {
    return new Chart(canvas, {
      type: 'scatter',
      data: { datasets: [] },
      options: {
        animation: false,
        aspectRatio: 1,
        parsing: false,
        scales: {
          x: { title: { display: true, text: 'east error (m)' } },
          y: { title: { display: true, text: 'north error (m)' } },
        },
        plugins: { legend: { position: 'bottom' } },
      },
      plugins: [squarePlot],
    });
  }

  /**
   * An axis limit that shows the bulk of |values|: 1.2 x their 99th
   * percentile (at least floor), so a few wild epochs do not flatten the rest.
   * clipped: some values lie beyond it.
   */
  function robustLimit(values, floor = 1) {
    const abs = values.filter((v) => Number.isFinite(v)).map(Math.abs);
    const lim = Math.max(floor, 1.2 * percentile(abs, 0.99) || 0);
    const max = abs.reduce((a, b) => Math.max(a, b), 0);
    return { lim: niceCeil(lim), clipped: max > niceCeil(lim) };
  }

  function niceCeil(v) {
    const p = Math.pow(10, Math.floor(Math.log10(v)));
    for (const m of [1, 2, 2.5, 5, 10]) if (m * p >= v) return m * p;
    return 10 * p;
  }

  function scatterData(es, ns, cep50, cep95, latest) {
    const pts = [];
    for (let i = 0; i < es.length; i++) {
      if (es[i] === null || ns[i] === null || !Number.isFinite(es[i]) || !Number.isFinite(ns[i])) continue;
      pts.push({ x: es[i], y: ns[i] });
    }
    const r = robustLimit(pts.flatMap((p) => [p.x, p.y]).concat(Number.isFinite(cep95) ? [cep95 / 1.2] : []));
    const lim = r.lim;
    // Chart.js draws lower order last: the circles and 'now' over the cloud.
    const sets = [{ label: 'fix − truth', data: pts, backgroundColor: 'rgba(47,111,214,0.45)', pointRadius: 2, order: 3 }];
    if (Number.isFinite(cep50)) sets.push({ type: 'line', label: `CEP50 ${cep50.toFixed(2)} m`, data: circle(cep50),
                                     borderColor: '#1f9d3a', pointRadius: 0, borderWidth: 2, order: 1 });
    if (Number.isFinite(cep95)) sets.push({ type: 'line', label: `CEP95 ${cep95.toFixed(2)} m`, data: circle(cep95),
                                     borderColor: '#c0392b', pointRadius: 0, borderWidth: 2, order: 1 });
    if (latest) sets.push({ label: 'now', data: [latest], backgroundColor: '#000', pointRadius: 5, pointStyle: 'crossRot', order: 0,
                            borderColor: '#000', borderWidth: 2 });
    return { datasets: sets, lim, clipped: r.clipped };
  }

  /** Show [-lim, lim] on both axes of a scatter chart (squarePlot keeps metres per pixel equal). */
  function squareUpdate(chart, lim, mode) {
    const x = chart.options.scales.x;
    const y = chart.options.scales.y;
    x.min = y.min = -lim;
    x.max = y.max = lim;
    chart.update(mode);
  }

  /** Nearest-rank percentile of finite values (q in (0, 1]). */
  function percentile(values, q) {
    const v = values.filter((x) => x !== null && Number.isFinite(x)).sort((a, b) => a - b);
    if (!v.length) return NaN;
    return v[Math.min(v.length, Math.max(1, Math.ceil(q * v.length))) - 1];
  }

  function fmt(v, digits, unit = '') {
    return v === null || v === undefined || !Number.isFinite(v) ? '—' : `${Number(v).toFixed(digits)}${unit}`;
  }

  /** Fix a time chart's y axis to +-lim (symmetric) or [0, lim], saying when it clips. */
  function clipY(chart, values, symmetric, title) {
    const r = robustLimit(values);
    chart.options.scales.y.min = symmetric ? -r.lim : 0;
    chart.options.scales.y.max = r.lim;
    chart.options.scales.y.title.text = r.clipped ? `${title} (axis clipped at ${r.lim} m)` : title;
  }

  /** Text made safe to place in HTML. */
  const esc = (v) => String(v).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));

  /** A new element with attributes and inner HTML (the reports' pages are built from these). */
  function el(tag, attrs = {}, html = '') {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    e.innerHTML = html;
    return e;
  }

  return { stateColors, stateLabels, states, skyXY, skyChart, skyDatasets, cn0Chart, cn0Data, timeChart, series,
           scatterChart, scatterData, squareUpdate, circle, percentile, robustLimit, clipY, fmt, esc, el };
})();
