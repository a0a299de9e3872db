// SPDX-License-Identifier: Apache-2.0
// The report of `gnssemu sweep collect` (docs/sweep.md §Collect): renders the
// JSON in #report-data: counts, every metric against every axis that varies,
// and the worst cases with the command that reproduces each.
'use strict';

(() => {
  const G = GnssCharts;
  const d = JSON.parse(document.getElementById('report-data').textContent);
  const root = document.getElementById('report');
  const { esc, el } = G;

  root.appendChild(el('h1', {}, esc(d.title)));
  root.appendChild(el('ul', { class: 'inputs' }, d.inputs.map((s) => `<li>${esc(s)}</li>`).join('')));
  const col = (name) => d.columns.indexOf(name);
  const num = (v) => (v === '' ? NaN : Number(v));
  const grid = el('main');

  // Worst cases first: what a failsafe review reads.
  const w = el('section', { class: 'panel wide', id: 'panel-worst' },
    `<h2>Worst cases: largest horizontal error while a fix was reported</h2>`);
  const shown = ['task_id', ...d.axes, 'h_max_fix_m', 'h95_m', 'avail_3d', 'refix_s'];
  w.appendChild(el('table', { class: 'grid', id: 'worst' },
    `<thead><tr>${shown.map((c) => `<th>${esc(c)}</th>`).join('')}<th>reproduce</th></tr></thead><tbody>` +
    d.worst.map((i) => `<tr>${shown.map((c) => `<td>${esc(d.rows[i][col(c)])}</td>`).join('')}` +
      `<td><code>${esc(d.rows[i][col('reproduce')])}</code></td></tr>`).join('') + '</tbody>'));
  root.appendChild(w);
  root.appendChild(grid);

  // Every metric that has values against every axis with more than one value.
  let n = 0;
  for (const axis of d.axes) {
    const a = col(axis);
    const values = [...new Set(d.rows.map((r) => r[a]))];
    if (values.length < 2) continue;
    const numeric = values.every((v) => v !== '' && Number.isFinite(Number(v)));
    for (const m of d.metrics) {
      const k = col(m);
      const pts = d.rows.map((r) => ({ x: numeric ? Number(r[a]) : values.indexOf(r[a]), y: num(r[k]) }))
        .filter((p) => Number.isFinite(p.y));
      if (!pts.length) continue;
      const p = el('section', { class: 'panel', id: `panel-${n}` }, `<h2>${esc(m)} against ${esc(axis)}</h2>`);
      const b = el('div', { class: 'series' });
      const c = el('canvas', { id: `plot-${n++}` });
      b.appendChild(c);
      p.appendChild(b);
      grid.appendChild(p);
      new Chart(c, {
        type: 'scatter',
        data: { datasets: [{ label: m, data: pts, backgroundColor: 'rgba(47,111,214,0.5)', pointRadius: 3 }] },
        options: {
          animation: false, maintainAspectRatio: false, parsing: false,
          scales: {
            x: numeric ? { title: { display: true, text: axis } }
                       : { title: { display: true, text: axis }, min: -0.5, max: values.length - 0.5,
                           ticks: { stepSize: 1, callback: (v) => (values[v] || '').split('/').pop() } },
            y: { title: { display: true, text: m } },
          },
          plugins: { legend: { display: false } },
        },
      });
    }
  }
})();
