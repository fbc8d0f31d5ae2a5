"""Design margins: claims over tolerance boxes (pavings) and certified thresholds.

* :mod:`.paving`: the SIVIA-style paving of a scene's tolerance box, claim by claim: sub-boxes
  proved for every parameter in them, refuted for every parameter in them (with a re-proved
  counterexample point), or undecided at the resolution asked;
* :mod:`.ranges`: certified ranges of a kind's quantities over the box (outer and inner), worst-case
  margins and sensitivities, from the kind's optional ``box_quantities`` module;
* :mod:`.threshold`: certified bisection of one parameter, proved on one side, refuted on the other;
* :mod:`.executors`: where the independent sub-box evaluations run (in process, a process pool, Dask);
* :mod:`.report`: the paving certificate (JSON) and its Markdown report.

This is the application layer: it drives a kind's optional ``boxes`` module (the parametric rigour:
``BOX_CLAIMS``, ``validate_box``, ``evaluate_box``) and the point prover; it holds no mathematics.
"""
