"""Design margins: claims over tolerance boxes (pavings) and certified thresholds.

* :mod:`.paving`: the SIVIA-style paving of a scene's tolerance box, claim by claim: sub-boxes
  proved for every parameter in them, refuted for every parameter in them (with a re-proved
  counterexample point), or undecided at the resolution asked;
* :mod:`.ranges`: certified ranges of a kind's quantities over the box (outer and inner), worst-case
  margins and sensitivities, from the kind's optional ``box_quantities`` module;
* :mod:`.threshold`: certified bisection of one parameter, proved on one side, refuted on the other;
* :mod:`.order`, :mod:`.resume`: the best-first queue of an anytime paving; resuming and refining one;
* :mod:`.check`, :mod:`.sampled`: the paving checker, and its second path (the point prover at points of
  the decided sub-boxes);
* :mod:`.counterexamples`, :mod:`.counterexample_check`: counterexamples searched over every undecided
  leaf and a Monte Carlo failing fraction (not yet wired into the paving: see the module);
* :mod:`.safe_set`, :mod:`.export`, :mod:`.safe_set_command`: where the selected claims all hold, the
  certified yield, the leaves as CSV, ``rigor-gyro safe-set``;
* :mod:`.scan`: point proofs at N values of one parameter;
* :mod:`.executors`: where the independent sub-box evaluations run (in process, a process pool, Dask);
* :mod:`.report`, :mod:`.plots`: the paving certificate (JSON), its Markdown report and its figures.

This is the application layer: it drives a kind's optional ``boxes`` module (the parametric rigour:
``BOX_CLAIMS``, ``validate_box``, ``evaluate_box``) and the point prover; it holds no mathematics.
"""
