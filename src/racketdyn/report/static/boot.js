// Draws every interactive plot from the page's JSON data, then marks <body data-ready="1">.
(function () {
  "use strict";
  var rd = window.racketdyn;
  var D = JSON.parse(document.getElementById("report-data").textContent);
  D.maps.forEach(rd.drawMap);
  D.frf.forEach(rd.drawFrf);
  document.body.dataset.ready = "1";
})();
