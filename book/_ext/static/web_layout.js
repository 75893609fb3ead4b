// book/_ext/web_layout.py: mark the inline formulas wider than their line (web_layout.css lets
// them scroll), once MathJax has typeset the page and whenever the window changes width.
(function () {
  function mark() {
    document.querySelectorAll("mjx-container:not([display='true'])").forEach(function (m) {
      m.classList.remove("wide-inline");
      var line = m.closest("p, li, dd, dt, td, th, figcaption, div");
      if (line && m.getBoundingClientRect().width > line.clientWidth) {
        m.classList.add("wide-inline");
      }
    });
  }
  window.addEventListener("load", function () {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
      MathJax.startup.promise.then(mark);
    }
    window.addEventListener("resize", mark);
  });
})();
