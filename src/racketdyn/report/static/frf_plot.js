// Interactive FRF plot: |H| on a log scale over the coherence, one view per measurement point
// (buttons), identified natural frequencies as dashed lines; wheel or buttons zoom the
// frequency axis, drag pans, double-click resets, hover reads the values out.  The data (a
// "frf" entry of the page's JSON) come from racketdyn.report.sections.quality.
// racketdyn.drawFrf(spec).
(function () {
  "use strict";
  var rd = window.racketdyn = window.racketdyn || {};
  var kit = rd.kit, num = kit.num, esc = kit.esc, sci = kit.sci, buttons = kit.buttons;
  var niceStep = kit.niceStep;

  rd.drawFrf = function (spec) {
    var box = document.getElementById(spec.id), svg = box.querySelector("svg");
    var readout = box.querySelector(".readout"), controls = box.querySelector(".controls");
    var W = 900, L = 78, R = 14, PW = W - L - R, MT = 30, MH = 252, CT = 300, CH = 90;
    var f = spec.f, lo = f[0], hi = f[f.length - 1], x0 = lo, x1 = hi, view = 0, drag = null;
    var minSpan = 8 * (f[1] - f[0]);
    function X(v) { return L + (v - x0) / (x1 - x0) * PW; }
    function svgX(ev) {
      var r = svg.getBoundingClientRect();
      return (ev.clientX - r.left) * W / r.width;
    }
    function fAt(ev) { return x0 + (svgX(ev) - L) / PW * (x1 - x0); }
    function nearest(v) {
      var a = 0, b = f.length - 1;
      while (b - a > 1) { var m = (a + b) >> 1; if (f[m] < v) { a = m; } else { b = m; } }
      return v - f[a] < f[b] - v ? a : b;
    }
    function render() {
      var series = spec.views[view].series, i0 = Math.max(nearest(x0) - 1, 0);
      var i1 = Math.min(nearest(x1) + 1, f.length - 1), ymin = Infinity, ymax = -Infinity, s = "";
      series.forEach(function (sr) {
        for (var i = i0; i <= i1; i++) {
          var m = sr.mag[i];
          if (m > 0) { var l = Math.log10(m); ymin = Math.min(ymin, l); ymax = Math.max(ymax, l); }
        }
      });
      if (!isFinite(ymin)) { ymin = -3; ymax = 0; }
      ymin = Math.floor(ymin); ymax = Math.ceil(ymax);
      if (ymax === ymin) { ymax += 1; }
      function Y(m) { return MT + (ymax - Math.log10(m)) / (ymax - ymin) * MH; }
      function C(c) { return CT + (1 - c) * CH; }
      s += '<defs><clipPath id="' + spec.id + '-clip"><rect x="' + L + '" y="0" width="' + PW +
        '" height="440"/></clipPath></defs>';
      var step = niceStep(x1 - x0, 8);
      for (var t = Math.ceil(x0 / step) * step; t <= x1; t += step) {
        s += '<line x1="' + X(t) + '" x2="' + X(t) + '" y1="' + MT + '" y2="' + (CT + CH) +
          '" stroke="#e3e7eb"/><text x="' + X(t) + '" y="' + (CT + CH + 16) +
          '" font-size="12" text-anchor="middle">' + Number(t.toPrecision(6)) + "</text>";
      }
      for (var d = ymin; d <= ymax; d++) {
        s += '<line x1="' + L + '" x2="' + (L + PW) + '" y1="' + Y(Math.pow(10, d)) + '" y2="' +
          Y(Math.pow(10, d)) + '" stroke="#e3e7eb"/><text x="' + (L - 6) + '" y="' +
          (Y(Math.pow(10, d)) + 4) + '" font-size="12" text-anchor="end">1e' + d + "</text>";
      }
      [0, 0.5, 1].forEach(function (c) {
        s += '<line x1="' + L + '" x2="' + (L + PW) + '" y1="' + C(c) + '" y2="' + C(c) +
          '" stroke="#e3e7eb"/><text x="' + (L - 6) + '" y="' + (C(c) + 4) +
          '" font-size="12" text-anchor="end">' + c + "</text>";
      });
      s += '<g clip-path="url(#' + spec.id + '-clip)">';
      spec.modes.forEach(function (m) {
        if (m.f < x0 || m.f > x1) { return; }
        s += '<line x1="' + X(m.f) + '" x2="' + X(m.f) + '" y1="' + MT + '" y2="' + (MT + MH) +
          '" stroke="' + m.colour + '" stroke-opacity=".45" stroke-dasharray="4 3"/>';
      });
      var drawn = 0;
      series.forEach(function (sr) {
        var pm = [], pc = [];
        for (var i = i0; i <= i1; i++) {
          if (sr.mag[i] > 0) { pm.push(X(f[i]).toFixed(1) + "," + Y(sr.mag[i]).toFixed(1)); }
          if (sr.coh && sr.coh[i] !== null) {
            pc.push(X(f[i]).toFixed(1) + "," + C(sr.coh[i]).toFixed(1));
          }
        }
        drawn += pm.length;
        s += '<polyline class="mag" fill="none" stroke="' + sr.colour +
          '" stroke-width="1.3" points="' + pm.join(" ") + '"/>';
        if (pc.length) {
          s += '<polyline fill="none" stroke="' + sr.colour + '" stroke-width="1" points="' +
            pc.join(" ") + '"/>';
        }
      });
      s += "</g>";
      s += '<rect x="' + L + '" y="' + MT + '" width="' + PW + '" height="' + MH +
        '" fill="none" stroke="#888"/><rect x="' + L + '" y="' + CT + '" width="' + PW +
        '" height="' + CH + '" fill="none" stroke="#888"/>';
      s += '<text x="16" y="' + (MT + MH / 2) + '" font-size="12" text-anchor="middle" ' +
        'transform="rotate(-90 16 ' + (MT + MH / 2) + ')">|H| (' + esc(spec.unit) + ")</text>" +
        '<text x="16" y="' + (CT + CH / 2) + '" font-size="12" text-anchor="middle" ' +
        'transform="rotate(-90 16 ' + (CT + CH / 2) + ')">coherence</text>' +
        '<text x="' + (L + PW / 2) + '" y="432" font-size="12" text-anchor="middle">' +
        "frequency (Hz)</text>";
      series.forEach(function (sr, k) {
        var x = L + 200 * k;
        s += '<line x1="' + x + '" x2="' + (x + 22) + '" y1="14" y2="14" stroke="' + sr.colour +
          '" stroke-width="2"/><text x="' + (x + 28) + '" y="18" font-size="12">' +
          esc(sr.label) + "</text>";
      });
      if (spec.modes.length) {
        s += '<line x1="' + (L + 200 * series.length) + '" x2="' + (L + 200 * series.length + 22) +
          '" y1="14" y2="14" stroke="#888" stroke-dasharray="4 3"/><text x="' +
          (L + 200 * series.length + 28) + '" y="18" font-size="12">identified modes</text>';
      }
      s += '<line class="cursor" x1="0" x2="0" y1="' + MT + '" y2="' + (CT + CH) +
        '" stroke="#d62728" visibility="hidden"/>';
      svg.innerHTML = s;
      box.dataset.drawn = String(drawn);
      box.dataset.range = x0.toFixed(1) + "-" + x1.toFixed(1);
    }
    function zoom(centre, k) {
      var span = Math.min(Math.max((x1 - x0) * k, minSpan), hi - lo);
      centre = Math.max(x0, Math.min(x1, centre));
      var a = centre - (centre - x0) / (x1 - x0) * span;
      x0 = Math.max(lo, Math.min(a, hi - span));
      x1 = x0 + span;
      render();
    }
    function hover(ev) {
      if (drag) {
        var shift = (svgX(ev) - drag.x) / PW * (drag.b - drag.a);
        var a = Math.max(lo, Math.min(drag.a - shift, hi - (drag.b - drag.a)));
        x0 = a; x1 = a + (drag.b - drag.a); render();
      }
      var v = fAt(ev), line = svg.querySelector("line.cursor");
      if (v < x0 || v > x1) { line.setAttribute("visibility", "hidden"); return; }
      var i = nearest(v), out = "f = " + f[i].toFixed(1) + " Hz";
      spec.views[view].series.forEach(function (sr) {
        out += "\n" + sr.label + ": |H| = " + sci(sr.mag[i]) + " " + spec.unit +
          (sr.coh ? ", coherence " + num(sr.coh[i], 3) : "");
      });
      var near = null;
      spec.modes.forEach(function (m) {
        var gap = Math.abs(m.f - f[i]);
        if (gap <= Math.max(0.02 * f[i], 3 * (f[1] - f[0])) && (!near || gap < near.gap)) {
          near = { gap: gap, m: m };
        }
      });
      if (near) { out += "\nnear " + near.m.label + " at " + near.m.f.toFixed(1) + " Hz"; }
      readout.textContent = out;
      readout.style.whiteSpace = "pre";
      line.setAttribute("x1", X(f[i]));
      line.setAttribute("x2", X(f[i]));
      line.setAttribute("visibility", "visible");
    }
    buttons(controls, spec.views.map(function (v) { return v.label; }), 0, function (i) {
      view = i; render();
    });
    controls.insertAdjacentHTML("beforeend", '<span class="gap"></span>' +
      '<button type="button" data-zoom="0.5">zoom in</button>' +
      '<button type="button" data-zoom="2">zoom out</button>' +
      '<button type="button" data-zoom="0">reset</button>');
    controls.addEventListener("click", function (ev) {
      var b = ev.target.closest("button[data-zoom]");
      if (!b) { return; }
      var k = Number(b.dataset.zoom);
      if (k === 0) { x0 = lo; x1 = hi; render(); } else { zoom((x0 + x1) / 2, k); }
    });
    svg.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      zoom(fAt(ev), ev.deltaY < 0 ? 0.8 : 1.25);
    }, { passive: false });
    svg.addEventListener("mousedown", function (ev) {
      drag = { x: svgX(ev), a: x0, b: x1 };
      ev.preventDefault();
    });
    window.addEventListener("mouseup", function () { drag = null; });
    svg.addEventListener("mousemove", hover);
    svg.addEventListener("mouseleave", function () {
      var line = svg.querySelector("line.cursor");
      if (line) { line.setAttribute("visibility", "hidden"); }
    });
    svg.addEventListener("dblclick", function () { x0 = lo; x1 = hi; render(); });
    render();
  };
})();
