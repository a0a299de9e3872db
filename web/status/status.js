// SPDX-License-Identifier: Apache-2.0
// The live status page (docs/status.md): /api/status once for the history,
// then one status per epoch from /api/events (server-sent events). Renders
// only what that JSON carries. A fleet's receiver (?vehicle=ID&receiver=NAME
// in the page's address, picked in the header or in the overview table of
// every receiver, /api/overview once a second) is polled twice a second.
'use strict';

(() => {
  const G = GnssCharts;
  const $ = (id) => document.getElementById(id);
  const kHistory = 600;
  const hist = { t_s: [], e_m: [], n_m: [], u_m: [], h_acc_m: [], v_acc_m: [], fix_type: [], num_used: [], num_tracked: [] };

  const sky = G.skyChart($('sky'), { prnLabels: true });
  const cn0 = G.cn0Chart($('cn0'));
  const error = G.timeChart($('error'), 'error (m)');
  const scatter = G.scatterChart($('scatter'));
  const accuracy = G.timeChart($('accuracy'), 'm');
  let faults = null;

  function text(id, v) {
    const el = $(id);
    if (el && el.textContent !== v) el.textContent = v;
  }

  function appendHistory(h) {
    if (!h || !h.t_s) return;
    for (let i = 0; i < h.t_s.length; i++) {
      const t = h.t_s[i];
      const n = hist.t_s.length;
      if (n && t <= hist.t_s[n - 1]) {
        if (t < hist.t_s[n - 1]) for (const k of Object.keys(hist)) hist[k].length = 0;  // the run restarted
        else continue;
      }
      for (const k of Object.keys(hist)) hist[k].push(h[k] !== undefined ? h[k][i] : null);
    }
    const extra = hist.t_s.length - kHistory;
    if (extra > 0) for (const k of Object.keys(hist)) hist[k].splice(0, extra);
  }

  function renderFix(s) {
    const f = s.fix;
    const badge = $('fix-type');
    badge.textContent = f.type_name === 'none' ? 'no fix' : f.type_name === 'DR' ? 'dead reckoning' : `${f.type_name} fix`;
    badge.className = `badge badge-${f.type_name}`;
    badge.dataset.fixType = String(f.type);
    text('utc', s.epoch.utc || '—');
    text('gps-week', String(s.epoch.gps_week));
    text('tow', G.fmt(s.epoch.tow_s, 1));
    document.body.dataset.tow = String(s.epoch.tow_s);
    document.body.dataset.epoch = String(s.epoch.count);
    text('num-used', String(f.num_used));
    text('num-tracked', String(f.num_tracked));
    text('num-visible', String(f.num_visible));
    text('lat', G.fmt(f.lat_deg, 7, '°'));
    text('lon', G.fmt(f.lon_deg, 7, '°'));
    text('height', G.fmt(f.height_m, 2, ' m'));
    text('msl', G.fmt(f.msl_m, 2, ' m'));
    text('speed', G.fmt(f.speed_m_s, 2, ' m/s'));
    text('course', G.fmt(f.course_deg, 1, '°'));
    for (const k of ['pdop', 'hdop', 'vdop', 'gdop', 'tdop']) text(k, G.fmt(f.dop[k], 2));
    text('ttff', G.fmt(f.ttff_s, 1, ' s'));
    text('uptime', G.fmt(s.epoch.uptime_s, 0, ' s'));
    const e = s.error;
    text('h-acc', G.fmt(f.h_acc_m, 2, ' m'));
    text('v-acc', G.fmt(f.v_acc_m, 2, ' m'));
    text('h-err', G.fmt(e.h_m, 2, ' m'));
    text('v-err', G.fmt(e.v_m, 2, ' m'));
    $('h-err').className = e.valid && e.h_m > 3 * f.h_acc_m ? 'warn' : '';
    $('v-err').className = e.valid && e.v_m > 3 * f.v_acc_m ? 'warn' : '';
    text('cep50', G.fmt(e.cep50_m, 2, ' m'));
    text('cep95', G.fmt(e.cep95_m, 2, ' m'));
    text('cep-n', String(e.samples));
    const t = s.truth;
    text('truth-source', `${t.source}${t.source === 'simulator' && !t.fresh ? ' (stopped)' : ''}${t.valid ? '' : ', no truth'}`);
    text('truth-rate', G.fmt(t.rate_hz, 1, ' packets/s'));
    text('truth-packets', String(t.packets));
    text('truth-dropped', String(t.dropped));
    const reasons = Object.entries(t.drops || {}).map(([k, v]) => `${k} ${v}`).join(', ');
    text('truth-drops', reasons ? `(${reasons})` : '');
  }

  function renderSats(s) {
    const pts = s.satellites.map((x) => ({ sat: x.sat, prn: x.prn, az: x.az_deg, el: x.el_deg, cn0: x.cn0_dbhz, state: x.state, used: x.used }));
    sky.data.datasets = G.skyDatasets(pts, s.settings.elevation_mask_deg, 7);
    sky.update('none');
    cn0.data = G.cn0Data(s.satellites, s.settings.acquire_dbhz, s.settings.lose_dbhz);
    cn0.update('none');
    const body = $('sat-table').tBodies[0];
    const rows = s.satellites.map((x) => {
      const tr = document.createElement('tr');
      tr.dataset.prn = String(x.prn);
      tr.dataset.sat = x.sat;
      tr.dataset.state = x.state;
      const cells = [
        `<span class="state" style="background:${G.stateColors[x.state]}"></span>${x.sat}`,
        G.stateLabels[x.state] || x.state,
        G.fmt(x.az_deg, 1), G.fmt(x.el_deg, 1), x.tracked ? G.fmt(x.cn0_dbhz, 1) : '—',
        G.fmt(x.residual_m, 2), G.fmt(x.nlos_delay_m, 1),
      ];
      tr.innerHTML = cells.map((c) => `<td>${c}</td>`).join('');
      return tr;
    });
    body.replaceChildren(...rows);
  }

  // What port events did (docs/faults.md §5): the counters that are not 0.
  const LINK_COUNTERS = [['link_bytes_lost', 'bytes lost'], ['link_messages_corrupted', 'messages corrupted'],
    ['link_messages_dropped', 'messages dropped'], ['link_epochs_delayed', 'epochs delayed'],
    ['link_epochs_frozen', 'epochs frozen'], ['link_epochs_stopped', 'epochs stopped'],
    ['link_replies_stopped', 'replies stopped'], ['link_epochs_skipped', 'epochs skipped'],
    ['link_epochs_wrong_fix', 'epochs with a wrong fix']];
  const linkText = (p) => LINK_COUNTERS.filter(([k]) => p[k] > 0).map(([k, what]) => `${p[k]} ${what}`).join(', ') || '—';

  function renderPorts(s) {
    const body = $('port-table').tBodies[0];
    const esc = (v) => String(v).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
    body.replaceChildren(...s.ports.map((p) => {
      const tr = document.createElement('tr');
      tr.dataset.port = p.name;
      const cells = [esc(p.name), esc(p.type), esc(p.where), esc(p.protocols), p.baud ? String(p.baud) : '—',
        G.fmt(p.bytes_per_s, 0), p.line_use === null ? 'no line' : G.fmt(100 * p.line_use, 1, ' %'),
        p.tx_fill === null ? '—' : G.fmt(100 * p.tx_fill, 1, ' %'), String(p.epochs_written),
        String(p.epochs_dropped), String(p.messages_dropped), linkText(p)];
      tr.innerHTML = cells.map((c) => `<td>${c}</td>`).join('');
      if (p.line_use !== null && p.line_use > 1) tr.className = 'warn';
      return tr;
    }));
  }

  function renderFaults(s, now) {
    const list = s.faults || [];
    $('fault-none').style.display = list.length ? 'none' : '';
    $('fault-timeline-box').style.display = list.length ? '' : 'none';
    if (!list.length) return;
    if (!faults) {
      faults = new Chart($('fault-timeline'), {
        type: 'bar',
        data: { labels: [], datasets: [] },
        options: { animation: false, maintainAspectRatio: false, indexAxis: 'y', parsing: true,
                   scales: { x: { type: 'linear', title: { display: true, text: 'run time (s)' } } },
                   plugins: { legend: { display: false } } },
      });
    }
    faults.data.labels = list.map((f) => `${f.type} ${f.id}`);
    faults.data.datasets = [{
      data: list.map((f) => [f.start_s, f.end_s === null ? now : f.end_s]),
      backgroundColor: list.map((f) => (f.active ? '#c0392b' : '#9aa3ad')),
    }];
    faults.update('none');
  }

  function renderHistory(s) {
    error.data.datasets = [
      G.series('east', '#2f6fd6', hist.t_s, hist.e_m),
      G.series('north', '#1f9d3a', hist.t_s, hist.n_m),
      G.series('up', '#e08a00', hist.t_s, hist.u_m),
    ];
    G.clipY(error, hist.e_m.concat(hist.n_m, hist.u_m), true, 'error (m)');
    error.update('none');
    const h = hist.e_m.map((e, i) => (e === null || hist.n_m[i] === null ? null : Math.hypot(e, hist.n_m[i])));
    const v = hist.u_m.map((u) => (u === null ? null : Math.abs(u)));
    accuracy.data.datasets = [
      G.series('horizontal error', '#2f6fd6', hist.t_s, h),
      G.series('hAcc (reported)', '#0b2f6b', hist.t_s, hist.h_acc_m, { borderDash: [6, 3], borderWidth: 2.5, order: -1 }),
      G.series('vertical error', '#e08a00', hist.t_s, v),
      G.series('vAcc (reported)', '#7a4500', hist.t_s, hist.v_acc_m, { borderDash: [6, 3], borderWidth: 2.5, order: -1 }),
    ];
    G.clipY(accuracy, h.concat(v, hist.h_acc_m, hist.v_acc_m), false, 'm');
    accuracy.update('none');
    const e = s.error;
    const sd = G.scatterData(hist.e_m, hist.n_m, e.cep50_m, e.cep95_m, e.valid ? { x: e.e_m, y: e.n_m } : null);
    scatter.data.datasets = sd.datasets;
    G.squareUpdate(scatter, sd.lim, 'none');
  }

  function render(s) {
    appendHistory(s.history);
    renderFix(s);
    renderSats(s);
    renderPorts(s);
    renderFaults(s, s.epoch.run_s);
    renderHistory(s);
  }

  const params = new URLSearchParams(location.search);
  const vehicle = params.get('vehicle');
  const pick = vehicle
    ? '&vehicle=' + encodeURIComponent(vehicle) + '&receiver=' + encodeURIComponent(params.get('receiver') || '')
    : '';

  // ?rows=N: overview rows per page (/api/overview's limit, 1..1000).
  const pageRows = Math.min(1000, Math.max(1, parseInt(params.get('rows'), 10) || 1000));
  const pickSearch = (v, r) => '?vehicle=' + encodeURIComponent(v) + '&receiver=' + encodeURIComponent(r)
    + (params.has('rows') ? '&rows=' + pageRows : '');

  // The fleet overview (/api/overview): one row per receiver, refreshed every
  // second, in the configuration's order until a column is clicked; a click
  // on a row picks that receiver as the selector does. The daemon orders the
  // whole fleet (?sort=, ?order=) before it pages (previous / next), so the
  // first page of a sorted column holds the fleet's first rows, not the
  // first page's rows reordered.
  const overview = { key: null, dir: 1, rows: [], shown: null, offset: 0, total: 0 };
  const fixText = (r) => (r.fix_type === 0 ? 'no fix' : r.fix_name === 'DR' ? 'dead reckoning'
    : r.fix_name + (r.carrier === 'fixed' ? ' RTK fixed' : r.carrier === 'float' ? ' RTK float' : r.diff ? ' DGNSS' : ''));
  const truthText = (r) => (r.truth_source === 'simulator'
    ? `${r.truth_fresh ? 'simulator' : 'stopped'}${r.truth_age_s === null ? '' : ', ' + G.fmt(r.truth_age_s, 1, ' s ago')}`
    : r.truth_source) + (r.truth_valid ? '' : ', no truth');
  const faultText = (r) => (r.faults_active === 0 ? '—'
    : r.active_faults.map((f) => `${f.type} ${f.id}`).join(', ')
      + (r.faults_active > r.active_faults.length ? ` +${r.faults_active - r.active_faults.length}` : ''));
  function renderOverview() {
    const rows = overview.rows;  // in the daemon's order (?sort=)
    const body = $('overview-table').tBodies[0];
    body.replaceChildren(...rows.map((r) => {
      const tr = document.createElement('tr');
      Object.assign(tr.dataset, { vehicle: r.vehicle, receiver: r.receiver, fixType: String(r.fix_type),
        numUsed: String(r.num_used), faults: String(r.faults_active), epochs: String(r.epochs) });
      if (overview.shown && r.vehicle === overview.shown.vehicle && r.receiver === overview.shown.receiver) tr.className = 'picked';
      else if (r.faults_active > 0) tr.className = 'faulty';
      const cells = [`${r.vehicle}/${r.receiver}`, fixText(r), `${r.num_used} / ${r.num_tracked} / ${r.num_visible}`,
        G.fmt(r.h_err_m, 2, ' m'), G.fmt(r.h_acc_m, 2, ' m'), truthText(r), faultText(r),
        String(r.bytes_written), `${r.epochs_dropped} / ${r.messages_dropped}`];
      for (const c of cells) tr.appendChild(document.createElement('td')).textContent = c;
      tr.title = `show ${r.vehicle}/${r.receiver}`;
      tr.onclick = () => { location.search = pickSearch(r.vehicle, r.receiver); };
      return tr;
    }));
    for (const th of $('overview-table').tHead.rows[0].cells) {
      th.dataset.sorted = th.dataset.key === overview.key ? (overview.dir > 0 ? 'up' : 'down') : '';
    }
  }

  function loadOverview() {
    const sort = overview.key ? `&sort=${overview.key}&order=${overview.dir > 0 ? 'asc' : 'desc'}` : '';
    return fetch(`/api/overview?limit=${pageRows}&offset=${overview.offset}${sort}`)
      .then((r) => (r.ok ? r.json() : Promise.reject(new Error(`/api/overview: ${r.status}`))))
      .then((o) => {
        overview.total = o.total;
        if (o.rows.length === 0 && o.total > 0 && overview.offset > 0) {  // the fleet shrank under this page
          overview.offset = Math.floor((o.total - 1) / pageRows) * pageRows;
          return loadOverview();
        }
        overview.rows = o.rows;
        text('overview-count', o.total > o.rows.length
          ? `(${overview.offset + 1}–${overview.offset + o.rows.length} of ${o.total})` : `(${o.total})`);
        $('overview-pages').hidden = o.total <= pageRows;
        $('overview-prev').disabled = overview.offset === 0;
        $('overview-next').disabled = overview.offset + pageRows >= o.total;
        renderOverview();
        return undefined;
      });
  }

  function pollOverview() {
    loadOverview()
      .catch((err) => console.warn('overview', err))
      .finally(() => setTimeout(pollOverview, 1000));
  }

  function turnOverviewPage(step) {
    overview.offset = Math.max(0, overview.offset + step * pageRows);
    loadOverview().catch((err) => console.warn('overview', err));
  }

  // The receiver selector and the overview: shown when the daemon runs more than one.
  fetch('/api/receivers')
    .then((r) => (r.ok ? r.json() : []))
    .then((list) => {
      if (list.length < 2) return;
      const sel = $('receiver-select');
      // Without ?vehicle= the page shows the first receiver (/api/status's default).
      const shown = vehicle ? list.find((x) => x.vehicle === vehicle && x.receiver === params.get('receiver')) : list[0];
      for (const x of list) {
        const o = document.createElement('option');
        o.value = pickSearch(x.vehicle, x.receiver);
        o.textContent = x.vehicle + '/' + x.receiver;
        o.selected = x === shown;
        if (o.selected) overview.shown = x;
        sel.appendChild(o);
      }
      sel.hidden = false;
      sel.onchange = () => { location.search = sel.value; };
      for (const th of $('overview-table').tHead.rows[0].cells) {
        th.onclick = () => {
          overview.dir = overview.key === th.dataset.key ? -overview.dir : 1;
          overview.key = th.dataset.key;
          overview.offset = 0;
          loadOverview().catch((err) => console.warn('overview', err));
        };
      }
      $('overview-prev').onclick = () => turnOverviewPage(-1);
      $('overview-next').onclick = () => turnOverviewPage(1);
      $('panel-overview').hidden = false;
      pollOverview();
    })
    .catch(() => {});

  function poll() {
    fetch('/api/status?history=1' + pick)
      .then((r) => r.json())
      .then((s) => {
        $('conn').textContent = 'live';
        $('conn').className = 'conn conn-on';
        render(s);
      })
      .catch(() => { $('conn').textContent = 'reconnecting…'; $('conn').className = 'conn conn-off'; })
      .finally(() => setTimeout(poll, 500));
  }

  function connect() {
    if (vehicle) {
      poll();
      return;
    }
    const es = new EventSource('/api/events');
    es.onopen = () => { $('conn').textContent = 'live'; $('conn').className = 'conn conn-on'; };
    es.onerror = () => { $('conn').textContent = 'reconnecting…'; $('conn').className = 'conn conn-off'; };
    es.onmessage = (m) => {
      try {
        render(JSON.parse(m.data));
      } catch (err) {
        console.error('status event', err);
      }
    };
  }

  fetch('/api/status' + (vehicle ? '?' + pick.slice(1) : ''))
    .then((r) => r.json())
    .then((s) => { if (s.epoch.count > 0) render(s); })
    .catch((err) => console.error('status', err))
    .finally(connect);
})();
