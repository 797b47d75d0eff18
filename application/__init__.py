"""The application: the ``ddg-oracle`` command (:mod:`.cli`) and what it needs: the job
runner (:mod:`.jobs`, :mod:`.cluster`), isolation of libraries (:mod:`.isolation`,
:mod:`.containment`), reports (:mod:`.report`, :mod:`.html_report`, :mod:`.causes`),
mesh files and corpora (:mod:`.meshfiles`, :mod:`.corpus`), ``compare``, ``survey``,
the test vectors (:mod:`.vectors`), the traceability table and the pytest plugin.

The top layer: it imports every other one, and none imports it.
"""
