// SPDX-License-Identifier: Apache-2.0
// The HTML report of `gnssemu batch --report` and `gnssemu plot` (docs/cli.md
// §Report): renders the JSON in #report-data with the shared charts.
'use strict';

(() => {
  const G = GnssCharts;
  const d = JSON.parse(document.getElementById('report-data').textContent);
  const root = document.getElementById('report');
  const { esc, el } = G;

  /** A panel with a heading and a canvas in a box of the given class. */
  function panel(id, title, box = 'series', wide = false) {
    const p = el('section', { class: `panel${wide ? ' wide' : ''}`, id: `panel-${id}` }, `<h2>${esc(title)}</h2>`);
    const b = el('div', { class: box });
    const c = el('canvas', { id });
    b.appendChild(c);
    p.appendChild(b);
    grid.appendChild(p);
    return c;
  }

  root.appendChild(el('h1', {}, esc(d.title)));
  root.appendChild(el('ul', { class: 'inputs' }, d.inputs.map((s) => `<li>${esc(s)}</li>`).join('')));
  const s = d.summary;
  const pct = s.epochs ? (100 * s.fixes) / s.epochs : 0;
  const rows = [
    ['epochs', `${s.epochs}${d.epochs.stride > 1 ? ` (plots show every ${d.epochs.stride}th)` : ''}`],
    ['fixes', `${s.fixes} (${pct.toFixed(1)} %), 3D ${s.fixes_3d}`],
    ['horizontal error', `CEP50 ${G.fmt(s.cep50_m, 2, ' m')}, CEP95 ${G.fmt(s.cep95_m, 2, ' m')}, rms ${G.fmt(s.h_rms_m, 2, ' m')}, max ${G.fmt(s.h_max_m, 2, ' m')}`],
    ['vertical error', `50 % ${G.fmt(s.v50_m, 2, ' m')}, 95 % ${G.fmt(s.v95_m, 2, ' m')}, rms ${G.fmt(s.v_rms_m, 2, ' m')}`],
  ];
  const counts = Object.entries(d.state_counts || {}).filter(([, n]) => n > 0);
  const total = counts.reduce((a, [, n]) => a + n, 0);
  if (total) {
    rows.push(['satellite-epochs', counts.map(([k, n]) => `${G.stateLabels[k] || k} ${(100 * n / total).toFixed(1)} %`).join(', ')]);
  }
  if (s.epochs) {
    root.appendChild(el('table', { class: 'kv', id: 'summary' },
      rows.map(([k, v]) => `<tr><th>${esc(k)}</th><td>${esc(v)}</td></tr>`).join('')));
  }
  const grid = el('main');
  root.appendChild(grid);

  const e = d.epochs;
  const hasEpochs = e.t_s.length > 0;
  const hasSky = d.sky.t_s.length > 0;

  if (hasSky) {
    const sky = G.skyChart(panel('sky', 'Sky over the run', 'sky'));
    const pts = d.sky.t_s.map((t, i) => ({ sat: d.sky.sat ? d.sky.sat[i] : undefined, prn: d.sky.prn[i], az: d.sky.az[i], el: d.sky.el[i], cn0: d.sky.cn0[i],
                                           state: d.sky.state[i], used: d.sky.used[i] === 1 }));
    // Short runs draw short tracks: bigger points keep them visible.
    sky.data.datasets = G.skyDatasets(pts, Number.isFinite(d.elevation_mask_deg) ? d.elevation_mask_deg : 0,
                                      pts.length < 8000 ? 3 : 1.8, 0.4);
    sky.update();

    // C/N0 against elevation: this run, and a real receiver's when given.
    const c = new Chart(panel('cn0-el', 'C/N0 against elevation', 'series'), {
      type: 'scatter',
      data: { datasets: [] },
      options: { animation: false, maintainAspectRatio: false, parsing: false,
                 scales: { x: { min: 0, max: 90, title: { display: true, text: 'elevation (°)' } },
                           y: { title: { display: true, text: 'C/N0 (dB-Hz)' } } },
                 plugins: { legend: { position: 'bottom' } } },
    });
    const thin = (xs, ys, max) => {
      const k = Math.max(1, Math.ceil(xs.length / max));
      const out = [];
      for (let i = 0; i < xs.length; i += k) if (ys[i] > 0) out.push({ x: xs[i], y: ys[i] });
      return out;
    };
    const mid = (b) => (b.el_lo_deg + b.el_hi_deg) / 2;
    const sets = [
      { label: 'this run', data: thin(d.sky.el, d.sky.cn0, 8000), backgroundColor: 'rgba(47,111,214,0.25)', pointRadius: 1.5 },
      { type: 'line', label: 'this run, median per 5°', data: d.cn0_bins.filter((b) => b.sim_n > 0).map((b) => ({ x: mid(b), y: b.sim_median_dbhz })),
        borderColor: '#2f6fd6', backgroundColor: '#2f6fd6', pointRadius: 3, borderWidth: 2 },
    ];
    if (d.reference) {
      sets.push({ label: `${d.reference.source}`, data: thin(d.reference.el, d.reference.cn0, 8000),
                  backgroundColor: 'rgba(224,138,0,0.3)', pointRadius: 1.5 });
      sets.push({ type: 'line', label: `${d.reference.source}, median per 5°`,
                  data: d.cn0_bins.filter((b) => b.ref_n > 0).map((b) => ({ x: mid(b), y: b.ref_median_dbhz })),
                  borderColor: '#e08a00', backgroundColor: '#e08a00', pointRadius: 3, borderWidth: 2 });
    }
    if (Number.isFinite(d.acquire_dbhz)) {
      sets.push({ type: 'line', label: `acquire ${d.acquire_dbhz} dB-Hz`, data: [{ x: 0, y: d.acquire_dbhz }, { x: 90, y: d.acquire_dbhz }],
                  borderColor: '#1f9d3a', borderDash: [6, 3], pointRadius: 0, borderWidth: 1 });
      sets.push({ type: 'line', label: `lose lock ${d.lose_dbhz} dB-Hz`, data: [{ x: 0, y: d.lose_dbhz }, { x: 90, y: d.lose_dbhz }],
                  borderColor: '#c0392b', borderDash: [2, 3], pointRadius: 0, borderWidth: 1 });
    }
    c.data.datasets = sets;
    c.update();
    if (d.reference) {
      const bins = d.cn0_bins.filter((b) => b.sim_n > 0 || b.ref_n > 0);
      const both = bins.filter((b) => b.sim_n > 0 && b.ref_n > 0);
      const mad = both.reduce((a, b) => a + Math.abs(b.sim_median_dbhz - b.ref_median_dbhz), 0) / Math.max(1, both.length);
      const t = el('section', { class: 'panel', id: 'panel-cn0-bins' }, '<h2>C/N0 medians per elevation bin (dB-Hz)</h2>');
      t.appendChild(el('table', { class: 'grid', id: 'cn0-bins' },
        `<thead><tr><th>elevation</th><th>this run</th><th>n</th><th>${esc(d.reference.source)}</th><th>n</th><th>difference</th></tr></thead><tbody>` +
        bins.map((b) => `<tr><td>${b.el_lo_deg}–${b.el_hi_deg}°</td><td>${G.fmt(b.sim_median_dbhz, 1)}</td><td>${b.sim_n}</td>` +
          `<td>${G.fmt(b.ref_median_dbhz, 1)}</td><td>${b.ref_n}</td><td>${b.sim_n > 0 && b.ref_n > 0 ? G.fmt(b.sim_median_dbhz - b.ref_median_dbhz, 1) : '—'}</td></tr>`).join('') +
        `</tbody><tfoot><tr><td colspan="5">mean |difference| over ${both.length} bins with both</td><td>${G.fmt(mad, 2)}</td></tr></tfoot>`));
      grid.appendChild(t);
    }
  }

  if (hasEpochs) {
    const err = G.timeChart(panel('error', 'Position error against truth (fix − truth, local ENU)', 'series', true), 'error (m)');
    err.data.datasets = [
      G.series('east', '#2f6fd6', e.t_s, e.e_m),
      G.series('north', '#1f9d3a', e.t_s, e.n_m),
      G.series('up', '#e08a00', e.t_s, e.u_m),
    ];
    G.clipY(err, e.e_m.concat(e.n_m, e.u_m), true, 'error (m)');
    err.update();

    const h = e.e_m.map((x, i) => (x === null || e.n_m[i] === null ? null : Math.hypot(x, e.n_m[i])));
    if (e.h_acc_m.some((x) => x !== null)) {
      const acc = G.timeChart(panel('accuracy', 'Reported accuracy beside the actual error', 'series'), 'm');
      acc.data.datasets = [
        G.series('horizontal error', '#2f6fd6', e.t_s, h),
        G.series('hAcc (reported)', '#0b2f6b', e.t_s, e.h_acc_m, { borderDash: [6, 3], borderWidth: 2.5, order: -1 }),
        G.series('vertical error', '#e08a00', e.t_s, e.u_m.map((u) => (u === null ? null : Math.abs(u)))),
        G.series('vAcc (reported)', '#7a4500', e.t_s, e.v_acc_m, { borderDash: [6, 3], borderWidth: 2.5, order: -1 }),
      ];
      G.clipY(acc, h.concat(e.u_m, e.h_acc_m, e.v_acc_m), false, 'm');
      acc.update();
    }

    if (d.cdf.h_m.length) {
      const cdf = G.timeChart(panel('cdf', 'Horizontal error CDF', 'series'), 'fraction of fixes', 'horizontal error (m)');
      cdf.options.scales.y.min = 0;
      cdf.options.scales.y.max = 1;
      cdf.data.datasets = [G.series('horizontal error', '#2f6fd6', d.cdf.h_m, d.cdf.p, { stepped: true })];
      for (const [name, v, color] of [['CEP50', s.cep50_m, '#1f9d3a'], ['CEP95', s.cep95_m, '#c0392b']]) {
        if (Number.isFinite(v)) cdf.data.datasets.push({ label: `${name} ${v.toFixed(2)} m`, data: [{ x: v, y: 0 }, { x: v, y: 1 }],
                                                  borderColor: color, borderDash: [6, 3], borderWidth: 1.5 });
      }
      const r = G.robustLimit(d.cdf.h_m);
      cdf.options.scales.x.min = 0;
      cdf.options.scales.x.max = r.lim;
      if (r.clipped) cdf.options.scales.x.title.text = `horizontal error (m; axis clipped at ${r.lim} m, max ${G.fmt(s.h_max_m, 1)} m)`;
      cdf.update();
    }

    const sc = G.scatterChart(panel('scatter', 'Horizontal error', 'sky'));
    const sd = G.scatterData(e.e_m, e.n_m, s.cep50_m, s.cep95_m, null);
    sc.data.datasets = sd.datasets;
    G.squareUpdate(sc, sd.lim);

    const n = G.timeChart(panel('sats', 'Satellites over time', 'series', true), 'satellites');
    n.options.scales.y.min = 0;
    n.data.datasets = [];
    // Often equal: wide lines under narrow ones keep each visible.
    if (e.visible.some((x) => x !== null)) n.data.datasets.push(G.series('above the mask', '#9aa3ad', e.t_s, e.visible, { stepped: true, borderWidth: 6, order: 3 }));
    if (e.tracked.some((x) => x !== null)) n.data.datasets.push(G.series('tracked', '#2f6fd6', e.t_s, e.tracked, { stepped: true, borderWidth: 3.5, order: 2 }));
    n.data.datasets.push(G.series('used', '#1f9d3a', e.t_s, e.used, { stepped: true, borderWidth: 1.5, order: 1 }));
    n.data.datasets.push(G.series('fix type', '#c0392b', e.t_s, e.fix_type, { stepped: true, borderDash: [3, 3] }));
    n.update();
  }

  if (d.multipath.length) {
    const m = new Chart(panel('multipath', 'bench multipath: time per epoch against error', 'series', true), {
      type: 'scatter',
      data: { datasets: [
        { label: 'fix vs reference, rms (m)', data: d.multipath.map((r) => ({ x: r.us_mean, y: r.pos_err_rms_m, label: r.label })),
          backgroundColor: '#2f6fd6', pointRadius: 5 },
        { label: 'NLOS delay error, rms (m)', data: d.multipath.map((r) => ({ x: r.us_mean, y: r.nlos_delay_err_rms_m, label: r.label })),
          backgroundColor: '#e08a00', pointRadius: 5, pointStyle: 'triangle' },
      ] },
      options: { animation: false, maintainAspectRatio: false, parsing: false,
                 scales: { x: { type: 'logarithmic', title: { display: true, text: 'CPU time per epoch, mean (µs)' } },
                           y: { title: { display: true, text: 'error (m)' } } },
                 plugins: { legend: { position: 'bottom' },
                            tooltip: { callbacks: { label: (c) => `${c.raw.label}: ${c.raw.y.toFixed(2)} m at ${c.raw.x.toFixed(0)} µs` } } } },
    });
    m.update();
    const t = el('section', { class: 'panel wide', id: 'panel-multipath-table' }, '<h2>bench multipath settings</h2>');
    t.appendChild(el('table', { class: 'grid' },
      '<thead><tr><th>search</th><th>µs/epoch mean</th><th>p95</th><th>fix vs reference rms (m)</th><th>max (m)</th><th>NLOS delay err rms (m)</th><th>misclassified (%)</th></tr></thead><tbody>' +
      d.multipath.map((r) => `<tr><td>${esc(r.label)}</td><td>${G.fmt(r.us_mean, 0)}</td><td>${G.fmt(r.us_p95, 0)}</td><td>${G.fmt(r.pos_err_rms_m, 2)}</td>` +
        `<td>${G.fmt(r.pos_err_max_m, 2)}</td><td>${G.fmt(r.nlos_delay_err_rms_m, 2)}</td><td>${G.fmt(r.misclassified_pct, 2)}</td></tr>`).join('') + '</tbody>'));
    grid.appendChild(t);
  }
  document.body.dataset.rendered = 'true';
})();
