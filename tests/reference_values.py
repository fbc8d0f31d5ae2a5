"""Reference values with their provenance: (id, model, parameters, quantity, value, source).

Values come from computations independent of rigor_gyro's code path (mpmath at 50 digits on the form
(2) of the paper, with the nus from the quadratics (4)); each is accurate to far more digits than
any test needs, and a test checks that the certified ball overlaps (or contains) it.
"""

RUDENKO = {"a": "15.08", "b": "6.154", "eps": "0.1076", "Omega2": "0.629"}
_MP = "mpmath 1.3, 50 digits, polyroots of w N(w) - Omega^2 D(w) from Rudenko (1976) form (2)"

REFERENCE = [
    ("rud.omega1", "eigenfrequencies", RUDENKO, "omega_1", "0.0045024015725098391760238683167284442448640193014566", _MP),
    ("rud.omega2", "eigenfrequencies", RUDENKO, "omega_2", "0.038780822994197088395783315981043170219244196823387", _MP),
    ("rud.omega3", "eigenfrequencies", RUDENKO, "omega_3", "0.71259630259763191784556386305106929488134892705394", _MP),
    ("rud.omega4", "eigenfrequencies", RUDENKO, "omega_4", "2.2941002512943562886609485921376765705137326022649", _MP),
    ("rud.nu1", "eigenfrequencies", RUDENKO, "nu_1", "0.010821499443353065611686388801044643036777957619765", _MP),
    ("rud.nu2", "eigenfrequencies", RUDENKO, "nu_2", "0.029453435972293466839853490682666238270877948668305", _MP),
    ("rud.nu3", "eigenfrequencies", RUDENKO, "nu_3", "0.19402405898331393092743500194024058983313930927435", _MP),
    ("rud.nu4", "eigenfrequencies", RUDENKO, "nu_4", "0.21613422003202813753919824874523224698927247854962", _MP),
    ("rud.nu5", "eigenfrequencies", RUDENKO, "nu_5", "1.1940240589833139309274350019402405898331393092743", _MP),
    ("rud.nu6", "eigenfrequencies", RUDENKO, "nu_6", "1.1975022835030877363110311468636106517551724875011", _MP),
]
