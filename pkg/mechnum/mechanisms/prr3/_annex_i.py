"""The coefficients of the study's degree-8 polynomial as typeset in its Annex I (eq. 152).

The thesis prints ``C0 ... C8`` twice: typeset in Annex I and as Matlab code in Annex II. The
code is right; the typeset text is not (a product ``K_i K_j`` printed ``K_i^2 K_j``, ``Q5 Q6``
printed ``Q5^2 Q6``). :data:`ANNEX_I` keeps the typeset text term by term, in the study's order
with its coefficients and powers, written in one plain syntax (``4*K1^2*L^2*Q4^2``; the study's
``lambda`` is ``lambda1``), so that a chapter can audit every printed term against a symbolic
expansion; :func:`annex_i_terms` parses it.
"""

import re

#: Annex I's ``C_k``, as printed, keyed by ``k``.
ANNEX_I = {
    8: (
        "- K1^2*L^2*Q5^2 + 2*K1^2*L^2*Q5*Q6 - K1^2*L^2*Q6^2 + K1^2*Q5^2*lambda1^2 - "
        "2*K1^2*Q5*Q6*lambda1^2 + K1^2*Q6^2*lambda1^2 + K1^2*Q8^2 - 2*K1^2*Q8*Q9 + "
        "K1^2*Q9^2 + 2*K1^2*K2*L^2*Q5^2 - 4*K1^2*K2*L^2*Q5*Q6 + 2*K1^2*K2*L^2*Q6^2 - "
        "2*K1^2*K2*Q5^2*lambda1^2 + 4*K1^2*K2*Q5*Q6*lambda1^2 - "
        "2*K1^2*K2*Q6^2*lambda1^2 - 2*K1^2*K2*Q8^2 + 4*K1^2*K2*Q8*Q9 - 2*K1^2*K2*Q9^2 "
        "- 2*K1^2*K4*Q2*Q8 + 2*K1^2*K4*Q2*Q9 + 2*K1^2*K4*Q3*Q8 - 2*K1^2*K4*Q3*Q9 + "
        "2*K1^2*K4*Q5^2*lambda1^2 - 4*K1^2*K4*Q5*Q6*lambda1^2 + "
        "2*K1^2*K4*Q6^2*lambda1^2 + 2*K1^2*K5*Q2*Q8 - 2*K1^2*K5*Q2*Q9 - "
        "2*K1^2*K5*Q3*Q8 + 2*K1^2*K5*Q3*Q9 - 2*K1^2*K5*Q5^2*lambda1^2 + "
        "4*K1^2*K5*Q5*Q6*lambda1^2 - 2*K1^2*K5*Q6^2*lambda1^2 - K2^2*L^2*Q5^2 + "
        "2*K2^2*L^2*Q5*Q6 - K2^2*L^2*Q6^2 + K2^2*Q5^2*lambda1^2 - "
        "2*K2^2*Q5*Q6*lambda1^2 + K2^2*Q6^2*lambda1^2 + K2^2*Q8^2 - 2*K2^2*Q8*Q9 + "
        "K2^2*Q9^2 + 2*K2^2*K4*Q2*Q8 - 2*K2^2*K4*Q2*Q9 - 2*K2^2*K4*Q3*Q8 + "
        "2*K2^2*K4*Q3*Q9 - 2*K2^2*K4*Q5^2*lambda1^2 + 4*K2^2*K4*Q5*Q6*lambda1^2 - "
        "2*K2^2*K4*Q6^2*lambda1^2 - 2*K2^2*K5*Q2*Q8 + 2*K2^2*K5*Q2*Q9 + "
        "2*K2^2*K5*Q3*Q8 - 2*K2^2*K5*Q3*Q9 + 2*K2^2*K5*Q5^2*lambda1^2 - "
        "4*K2^2*K5*Q5*Q6*lambda1^2 + 2*K2^2*K5*Q6^2*lambda1^2 + K4^2*Q2^2 - "
        "2*K4^2*Q2*Q3 + K4^2*Q3^2 + K4^2*Q5^2 - 2*K4^2*Q5*Q6 + K4^2*Q6^2 - "
        "2*K4^2*K5*Q2^2 + 4*K4^2*K5*Q2*Q3 - 2*K4^2*K5*Q3^2 - 2*K4^2*K5*Q5^2 + "
        "4*K4^2*K5*Q5*Q6 - 2*K4^2*K5*Q6^2 + K5^2*Q2^2 - 2*K5^2*Q2*Q3 + K5^2*Q3^2 + "
        "K5^2*Q5^2 - 2*K5^2*Q5*Q6 + K5^2*Q6^2 "
    ),
    7: (
        "4*K4^2*Q1*Q3 - 4*K4^2*Q1*Q2 - 4*K5^2*Q1*Q2 + 4*K5^2*Q1*Q3 - 4*K4^2*Q4*Q5 + "
        "4*K4^2*Q4*Q6 - 4*K5^2*Q4*Q5 + 4*K5^2*Q4*Q6 - 4*K1^2*Q7*Q8 + 4*K1^2*Q7*Q9 - "
        "4*K2^2*Q7*Q8 + 4*K2^2*Q7*Q9 + 4*K1^2*L^2*Q4*Q5 - 4*K1^2*L^2*Q4*Q6 + "
        "4*K2^2*L^2*Q4*Q5 - 4*K2^2*L^2*Q4*Q6 - 4*K1^2*Q4*Q5*lambda1^2 + "
        "4*K1^2*Q4*Q6*lambda1^2 - 4*K2^2*Q4*Q5*lambda1^2 + 4*K2^2*Q4*Q6*lambda1^2 + "
        "8*K4^2*K5*Q1*Q2 - 8*K4^2*K5*Q1*Q3 + 4*K1^2*K4*Q1*Q8 + 4*K1^2*K4*Q2*Q7 - "
        "4*K1^2*K4*Q1*Q9 - 4*K1^2*K4*Q3*Q7 - 4*K1^2*K5*Q1*Q8 - 4*K1^2*K5*Q2*Q7 - "
        "4*K2^2*K4*Q1*Q8 - 4*K2^2*K4*Q2*Q7 + 4*K1^2*K5*Q1*Q9 + 4*K1^2*K5*Q3*Q7 + "
        "4*K2^2*K4*Q1*Q9 + 4*K2^2*K4*Q3*Q7 + 4*K2^2*K5*Q1*Q8 + 4*K2^2*K5*Q2*Q7 - "
        "4*K2^2*K5*Q1*Q9 - 4*K2^2*K5*Q3*Q7 + 8*K1^2*K2*Q7*Q8 + 8*K4^2*K5*Q4*Q5 - "
        "8*K1^2*K2*Q7*Q9 - 8*K4^2*K5*Q4*Q6 + 4*K3^2*K4*Q5*Q8 - 4*K3^2*K4*Q5*Q9 - "
        "4*K3^2*K4*Q6*Q8 - 4*K3^2*K5*Q5*Q8 + 4*K3^2*K4*Q6*Q9 + 4*K3^2*K5*Q5*Q9 + "
        "4*K3^2*K5*Q6*Q8 - 4*K3^2*K5*Q6*Q9 - 8*K1^2*K4*Q4*Q5*lambda1^2 + "
        "4*K3^2*K4*Q2*Q5*lambda1^2 + 8*K1^2*K4*Q4*Q6*lambda1^2 + "
        "8*K1^2*K5*Q4*Q5*lambda1^2 + 8*K2^2*K4*Q4*Q5*lambda1^2 - "
        "4*K3^2*K4*Q2*Q6*lambda1^2 - 4*K3^2*K4*Q3*Q5*lambda1^2 - "
        "4*K3^2*K5*Q2*Q5*lambda1^2 - 8*K1^2*K5*Q4*Q6*lambda1^2 - "
        "8*K2^2*K4*Q4*Q6*lambda1^2 - 8*K2^2*K5*Q4*Q5*lambda1^2 + "
        "4*K3^2*K4*Q3*Q6*lambda1^2 + 4*K3^2*K5*Q2*Q6*lambda1^2 + "
        "4*K3^2*K5*Q3*Q5*lambda1^2 + 4*K1^2*K3*Q5*Q8*lambda1^2 + "
        "8*K2^2*K5*Q4*Q6*lambda1^2 - 4*K3^2*K5*Q3*Q6*lambda1^2 - "
        "4*K1^2*K3*Q5*Q9*lambda1^2 - 4*K1^2*K3*Q6*Q8*lambda1^2 - "
        "4*K2^2*K3*Q5*Q8*lambda1^2 + 4*K1^2*K3*Q6*Q9*lambda1^2 + "
        "4*K2^2*K3*Q5*Q9*lambda1^2 + 4*K2^2*K3*Q6*Q8*lambda1^2 - "
        "4*K2^2*K3*Q6*Q9*lambda1^2 - 4*K1^2*K3*L^2*Q2*Q5 - 8*K1^2*K2*L^2*Q4*Q5 + "
        "4*K1^2*K3*L^2*Q2*Q6 + 4*K1^2*K3*L^2*Q3*Q5 + 4*K2^2*K3*L^2*Q2*Q5 + "
        "8*K1^2*K2*L^2*Q4*Q6 - 4*K1^2*K3*L^2*Q3*Q6 - 4*K2^2*K3*L^2*Q2*Q6 - "
        "4*K2^2*K3*L^2*Q3*Q5 + 4*K2^2*K3*L^2*Q3*Q6 + 4*K1^2*K3*Q2*Q5*lambda1^2 + "
        "8*K1^2*K2*Q4*Q5*lambda1^2 - 4*K1^2*K3*Q2*Q6*lambda1^2 - "
        "4*K1^2*K3*Q3*Q5*lambda1^2 - 4*K2^2*K3*Q2*Q5*lambda1^2 - "
        "8*K1^2*K2*Q4*Q6*lambda1^2 + 4*K1^2*K3*Q3*Q6*lambda1^2 + "
        "4*K2^2*K3*Q2*Q6*lambda1^2 + 4*K2^2*K3*Q3*Q5*lambda1^2 - "
        "4*K2^2*K3*Q3*Q6*lambda1^2 "
    ),
    6: (
        "- 4*K1^2*L^2*Q4^2 + 4*K1^2*L^2*Q5^2 - 4*K1^2*L^2*Q5*Q6 + "
        "4*K1^2*Q4^2*lambda1^2 - 4*K1^2*Q5^2*lambda1^2 + 4*K1^2*Q5*Q6*lambda1^2 + "
        "4*K1^2*Q7^2 - 4*K1^2*Q8^2 + 4*K1^2*Q8*Q9 + 8*K1^2*K2*L^2*Q4^2 - "
        "4*K1^2*K2*L^2*Q5^2 + 4*K1^2*K2*L^2*Q6^2 - 8*K1^2*K2*Q4^2*lambda1^2 + "
        "4*K1^2*K2*Q5^2*lambda1^2 - 4*K1^2*K2*Q6^2*lambda1^2 - 8*K1^2*K2*Q7^2 + "
        "4*K1^2*K2*Q8^2 - 4*K1^2*K2*Q9^2 + 8*K1^2*K3*L^2*Q1*Q5 - 8*K1^2*K3*L^2*Q1*Q6 "
        "+ 8*K1^2*K3*L^2*Q2*Q4 - 8*K1^2*K3*L^2*Q3*Q4 - 8*K1^2*K3*Q1*Q5*lambda1^2 + "
        "8*K1^2*K3*Q1*Q6*lambda1^2 - 8*K1^2*K3*Q2*Q4*lambda1^2 + "
        "8*K1^2*K3*Q3*Q4*lambda1^2 - 8*K1^2*K3*Q4*Q8*lambda1^2 + "
        "8*K1^2*K3*Q4*Q9*lambda1^2 - 8*K1^2*K3*Q5*Q7*lambda1^2 + "
        "8*K1^2*K3*Q6*Q7*lambda1^2 - 8*K1^2*K4*Q1*Q7 + 8*K1^2*K4*Q2*Q8 - "
        "4*K1^2*K4*Q2*Q9 - 4*K1^2*K4*Q3*Q8 + 8*K1^2*K4*Q4^2*lambda1^2 - "
        "8*K1^2*K4*Q5^2*lambda1^2 + 8*K1^2*K4*Q5*Q6*lambda1^2 + 8*K1^2*K5*Q1*Q7 - "
        "4*K1^2*K5*Q2*Q8 + 4*K1^2*K5*Q3*Q9 - 8*K1^2*K5*Q4^2*lambda1^2 + "
        "4*K1^2*K5*Q5^2*lambda1^2 - 4*K1^2*K5*Q6^2*lambda1^2 - 4*K2^2*L^2*Q4^2 + "
        "4*K2^2*L^2*Q5^2*Q6 - 4*K2^2*L^2*Q6^2 + 4*K2^2*Q4^2*lambda1^2 - "
        "4*K2^2*Q5^2*Q6*lambda1^2 + 4*K2^2*Q6^2*lambda1^2 + 4*K2^2*Q7^2 - "
        "4*K2^2*Q8*Q9 + 4*K2^2*Q9^2 - 8*K2*K3*L^2*Q1*Q5 + 8*K2*K3*L^2*Q1*Q6 - "
        "8*K2*K3*L^2*Q2*Q4 + 8*K2*K3*L^2*Q3*Q4 + 8*K2*K3*Q1*Q5*lambda1^2 - "
        "8*K2*K3*Q1*Q6*lambda1^2 + 8*K2*K3*Q2*Q4*lambda1^2 - 8*K2*K3*Q3*Q4*lambda1^2 "
        "+ 8*K2*K3*Q4*Q8*lambda1 - 8*K2*K3*Q4*Q9*lambda1 + 8*K2*K3*Q5*Q7*lambda1 - "
        "8*K2*K3*Q6*Q7*lambda1 + 8*K2*K4*Q1*Q7 - 4*K2*K4*Q2*Q8 + 4*K2*K4*Q3*Q9 - "
        "8*K2*K4*Q4^2*lambda1 + 4*K2*K4*Q5^2*lambda1 - 4*K2*K4*Q6^2*lambda1 - "
        "8*K2*K5*Q1*Q7 + 4*K2*K5*Q2*Q9 + 4*K2*K5*Q3*Q8 - 8*K2*K5*Q3*Q9 + "
        "8*K2*K5*Q4^2*lambda1 - 8*K2*K5*Q5*Q6*lambda1 + 8*K2*K5*Q6^2*lambda1 - "
        "4*K3^2*L^2*Q2^2 + 8*K3^2*L^2*Q2*Q3 - 4*K3^2*L^2*Q3^2 + 4*K3^2*Q2^2*lambda1^2 "
        "- 8*K3^2*Q2*Q3*lambda1^2 + 8*K3^2*Q2*Q8*lambda1 - 8*K3^2*Q2*Q9*lambda1 + "
        "4*K3^2*Q3^2*lambda1^2 - 8*K3^2*Q3*Q8*lambda1 + 8*K3^2*Q3*Q9*lambda1 + "
        "4*K3^2*Q8^2 - 8*K3^2*Q8*Q9 + 4*K3^2*Q9^2 - 8*K3*K4*Q1*Q5*lambda1 + "
        "8*K3*K4*Q1*Q6*lambda1 - 8*K3*K4*Q2*Q4*lambda1 + 8*K3*K4*Q3*Q4*lambda1 - "
        "8*K3*K4*Q4*Q8 + 8*K3*K4*Q4*Q9 - 8*K3*K4*Q5*Q7 + 8*K3*K4*Q6*Q7 + "
        "8*K3*K5*Q1*Q5*lambda1 - 8*K3*K5*Q1*Q6*lambda1 + 8*K3*K5*Q2*Q4*lambda1 - "
        "8*K3*K5*Q3*Q4*lambda1 + 8*K3*K5*Q4*Q8 - 8*K3*K5*Q4*Q9 + 8*K3*K5*Q5*Q7 - "
        "8*K3*K5*Q6*Q7 + 4*K4^2*Q1^2 - 4*K4^2*Q2^2 + 4*K4^2*Q2*Q3 + 4*K4^2*Q4^2 - "
        "4*K4^2*Q5^2 + 4*K4^2*Q5*Q6 - 8*K4*K5*Q1^2 + 4*K4*K5*Q2^2 - 4*K4*K5*Q3^2 - "
        "8*K4*K5*Q4^2 + 4*K4*K5*Q5^2 - 4*K4*K5*Q6^2 + 4*K5^2*Q1^2 - 4*K5^2*Q2*Q3 + "
        "4*K5^2*Q3^2 + 4*K5^2*Q4^2 - 4*K5^2*Q5*Q6 + 4*K5^2*Q6^2 "
    ),
    5: (
        "12*K4^2*Q1*Q2 - 4*K4^2*Q1*Q3 - 4*K5^2*Q1*Q2 + 12*K5^2*Q1*Q3 + 12*K4^2*Q4*Q5 "
        "- 4*K4^2*Q4*Q6 - 4*K5^2*Q4*Q5 + 12*K5^2*Q4*Q6 + 12*K1^2*Q7*Q8 - 4*K1^2*Q7*Q9 "
        "- 4*K2^2*Q7*Q8 + 12*K2^2*Q7*Q9 - 16*K3^2*Q7*Q8 + 16*K3^2*Q7*Q9 - "
        "16*K3^2*Q1*Q8*lambda1 - 16*K3^2*Q2*Q7*lambda1 + 16*K3^2*Q1*Q9*lambda1 + "
        "16*K3^2*Q3*Q7*lambda1 + 16*K3^2*L^2*Q1*Q2 - 16*K3^2*L^2*Q1*Q3 - "
        "12*K1^2*L^2*Q4*Q5 + 4*K1^2*L^2*Q4*Q6 + 4*K2^2*L^2*Q4*Q5 - 12*K2^2*L^2*Q4*Q6 "
        "- 16*K3^2*Q1*Q2*lambda1^2 + 16*K3^2*Q1*Q3*lambda1^2 + "
        "12*K1^2*Q4*Q5*lambda1^2 - 4*K1^2*Q4*Q6*lambda1^2 - 4*K2^2*Q4*Q5*lambda1^2 + "
        "12*K2^2*Q4*Q6*lambda1^2 - 8*K4*K5*Q1*Q2 - 8*K4*K5*Q1*Q3 - 12*K1*K4*Q1*Q8 - "
        "12*K1*K4*Q2*Q7 + 4*K1*K4*Q1*Q9 + 4*K1*K4*Q3*Q7 + 4*K1*K5*Q1*Q8 + "
        "4*K1*K5*Q2*Q7 + 4*K2*K4*Q1*Q8 + 4*K2*K4*Q2*Q7 + 4*K1*K5*Q1*Q9 + "
        "4*K1*K5*Q3*Q7 + 4*K2*K4*Q1*Q9 + 4*K2*K4*Q3*Q7 + 4*K2*K5*Q1*Q8 + "
        "4*K2*K5*Q2*Q7 - 12*K2*K5*Q1*Q9 - 12*K2*K5*Q3*Q7 - 8*K1*K2*Q7*Q8 + "
        "16*K3*K4*Q4*Q7 - 8*K4*K5*Q4*Q5 - 8*K1*K2*Q7*Q9 - 16*K3*K5*Q4*Q7 - "
        "8*K4*K5*Q4*Q6 - 12*K3*K4*Q5*Q8 + 4*K3*K4*Q5*Q9 + 4*K3*K4*Q6*Q8 + "
        "4*K3*K5*Q5*Q8 + 4*K3*K4*Q6*Q9 + 4*K3*K5*Q5*Q9 + 4*K3*K5*Q6*Q8 - "
        "12*K3*K5*Q6*Q9 + 16*K3*K4*Q1*Q4*lambda1 - 16*K3*K5*Q1*Q4*lambda1 + "
        "24*K1*K4*Q4*Q5*lambda1 - 12*K3*K4*Q2*Q5*lambda1 + 16*K1*K3*Q4*Q7*lambda1 - "
        "8*K1*K4*Q4*Q6*lambda1 - 8*K1*K5*Q4*Q5*lambda1 - 8*K2*K4*Q4*Q5*lambda1 + "
        "4*K3*K4*Q2*Q6*lambda1 + 4*K3*K4*Q3*Q5*lambda1 + 4*K3*K5*Q2*Q5*lambda1 - "
        "8*K1*K5*Q4*Q6*lambda1 - 16*K2*K3*Q4*Q7*lambda1 - 8*K2*K4*Q4*Q6*lambda1 - "
        "8*K2*K5*Q4*Q5*lambda1 + 4*K3*K4*Q3*Q6*lambda1 + 4*K3*K5*Q2*Q6*lambda1 + "
        "4*K3*K5*Q3*Q5*lambda1 - 12*K1*K3*Q5*Q8*lambda1 + 24*K2*K5*Q4*Q6*lambda1 - "
        "12*K3*K5*Q3*Q6*lambda1 + 4*K1*K3*Q5*Q9*lambda1 + 4*K1*K3*Q6*Q8*lambda1 + "
        "4*K2*K3*Q5*Q8*lambda1 + 4*K1*K3*Q6*Q9*lambda1 + 4*K2*K3*Q5*Q9*lambda1 + "
        "4*K2*K3*Q6*Q8*lambda1 - 12*K2*K3*Q6*Q9*lambda1 - 16*K1*K3*L^2*Q1*Q4 + "
        "16*K2*K3*L^2*Q1*Q4 + 12*K1*K3*L^2*Q2*Q5 + 8*K1*K2*L^2*Q4*Q5 - "
        "4*K1*K3*L^2*Q2*Q6 - 4*K1*K3*L^2*Q3*Q5 - 4*K2*K3*L^2*Q2*Q5 + "
        "8*K1*K2*L^2*Q4*Q6 - 4*K1*K3*L^2*Q3*Q6 - 4*K2*K3*L^2*Q2*Q6 - "
        "4*K2*K3*L^2*Q3*Q5 + 12*K2*K3*L^2*Q3*Q6 + 16*K1*K3*Q1*Q4*lambda1^2 - "
        "16*K2*K3*Q1*Q4*lambda1^2 - 12*K1*K3*Q2*Q5*lambda1^2 - "
        "8*K1*K2*Q4*Q5*lambda1^2 + 4*K1*K3*Q2*Q6*lambda1^2 + 4*K1*K3*Q3*Q5*lambda1^2 "
        "+ 4*K2*K3*Q2*Q5*lambda1^2 - 8*K1*K2*Q4*Q6*lambda1^2 + "
        "4*K1*K3*Q3*Q6*lambda1^2 + 4*K2*K3*Q2*Q6*lambda1^2 + 4*K2*K3*Q3*Q5*lambda1^2 "
        "- 12*K2*K3*Q3*Q6*lambda1^2 "
    ),
    4: (
        "8*K1^2*L^2*Q4^2 - 6*K1^2*L^2*Q5^2 + 2*K1^2*L^2*Q6^2 - 8*K1^2*Q4^2*lambda1^2 "
        "+ 6*K1^2*Q5^2*lambda1^2 - 2*K1^2*Q6^2*lambda1^2 - 8*K1^2*Q7^2 + 6*K1^2*Q8^2 "
        "- 2*K1^2*Q9^2 + 8*K1*K2*L^2*Q5*Q6 - 8*K1*K2*Q5*Q6*lambda1^2 - 8*K1*K2*Q8*Q9 "
        "- 16*K1*K3*L^2*Q1*Q5 - 16*K1*K3*L^2*Q2*Q4 + 16*K1*K3*Q1*Q5*lambda1^2 + "
        "16*K1*K3*Q2*Q4*lambda1^2 + 16*K1*K3*Q4*Q8*lambda1 + 16*K1*K3*Q5*Q7*lambda1 + "
        "16*K1*K4*Q1*Q7 - 12*K1*K4*Q2*Q8 + 4*K1*K4*Q3*Q9 - 16*K1*K4*Q4^2*lambda1 + "
        "12*K1*K4*Q5^2*lambda1 - 4*K1*K4*Q6^2*lambda1 + 4*K1*K5*Q2*Q9 + 4*K1*K5*Q3*Q8 "
        "- 8*K1*K5*Q5*Q6*lambda1 - 8*K2^2*L^2*Q4^2 + 2*K2^2*L^2*Q5^2 - "
        "6*K2^2*L^2*Q6^2 + 8*K2^2*Q4^2*lambda1^2 - 2*K2^2*Q5^2*lambda1^2 + "
        "6*K2^2*Q6^2*lambda1^2 + 8*K2^2*Q7^2 - 2*K2^2*Q8^2 + 6*K2^2*Q9^2 + "
        "16*K2*K3*L^2*Q1*Q6 + 16*K2*K3*L^2*Q3*Q4 - 16*K2*K3*Q1*Q6*lambda1^2 - "
        "16*K2*K3*Q3*Q4*lambda1^2 - 16*K2*K3*Q4*Q9*lambda1 - 16*K2*K3*Q6*Q7*lambda1 + "
        "4*K2*K4*Q2*Q9 + 4*K2*K4*Q3*Q8 - 8*K2*K4*Q5*Q6*lambda1 - 16*K2*K5*Q1*Q7 + "
        "4*K2*K5*Q2*Q8 - 12*K2*K5*Q3*Q9 + 16*K2*K5*Q4^2*lambda1 - "
        "4*K2*K5*Q5^2*lambda1 + 12*K2*K5*Q6^2*lambda1 - 16*K3^2*L^2*Q1^2 + "
        "8*K3^2*L^2*Q2^2 - 8*K3^2*L^2*Q3^2 + 16*K3^2*Q1^2*lambda1^2 + "
        "32*K3^2*Q1*Q7*lambda1 - 8*K3^2*Q2^2*lambda1^2 - 16*K3^2*Q2*Q8*lambda1 + "
        "8*K3^2*Q3^2*lambda1^2 + 16*K3^2*Q3*Q9*lambda1 + 16*K3^2*Q7^2 - 8*K3^2*Q8^2 + "
        "8*K3^2*Q9^2 + 16*K3*K4*Q1*Q5*lambda1 + 16*K3*K4*Q2*Q4*lambda1 + "
        "16*K3*K4*Q4*Q8 + 16*K3*K4*Q5*Q7 - 16*K3*K5*Q1*Q6*lambda1 - "
        "16*K3*K5*Q3*Q4*lambda1 - 16*K3*K5*Q4*Q9 - 16*K3*K5*Q6*Q7 - 8*K4^2*Q1^2 + "
        "6*K4^2*Q2^2 - 2*K4^2*Q3^2 - 8*K4^2*Q4^2 + 6*K4^2*Q5^2 - 2*K4^2*Q6^2 - "
        "8*K4*K5*Q2*Q3 - 8*K4*K5*Q5*Q6 + 8*K5^2*Q1^2 - 2*K5^2*Q2^2 + 6*K5^2*Q3^2 + "
        "8*K5^2*Q4^2 - 2*K5^2*Q5^2 + 6*K5^2*Q6^2 "
    ),
    3: (
        "4*K5^2*Q1*Q2 - 4*K4^2*Q1*Q3 - 12*K4^2*Q1*Q2 + 12*K5^2*Q1*Q3 - 12*K4^2*Q4*Q5 "
        "- 4*K4^2*Q4*Q6 + 4*K5^2*Q4*Q5 + 12*K5^2*Q4*Q6 - 12*K1^2*Q7*Q8 - 4*K1^2*Q7*Q9 "
        "+ 4*K2^2*Q7*Q8 + 12*K2^2*Q7*Q9 + 16*K3^2*Q7*Q8 + 16*K3^2*Q7*Q9 + "
        "16*K3^2*Q1*Q8*lambda1 + 16*K3^2*Q2*Q7*lambda1 + 16*K3^2*Q1*Q9*lambda1 + "
        "16*K3^2*Q3*Q7*lambda1 - 16*K3^2*L^2*Q1*Q2 - 16*K3^2*L^2*Q1*Q3 + "
        "12*K1^2*L^2*Q4*Q5 + 4*K1^2*L^2*Q4*Q6 - 4*K2^2*L^2*Q4*Q5 - 12*K2^2*L^2*Q4*Q6 "
        "+ 16*K3^2*Q1*Q2*lambda1^2 + 16*K3^2*Q1*Q3*lambda1^2 - "
        "12*K1^2*Q4*Q5*lambda1^2 - 4*K1^2*Q4*Q6*lambda1^2 + 4*K2^2*Q4*Q5*lambda1^2 + "
        "12*K2^2*Q4*Q6*lambda1^2 - 8*K4*K5*Q1*Q2 + 8*K4*K5*Q1*Q3 + 12*K1*K4*Q1*Q8 + "
        "12*K1*K4*Q2*Q7 + 4*K1*K4*Q1*Q9 + 4*K1*K4*Q3*Q7 + 4*K1*K5*Q1*Q8 + "
        "4*K1*K5*Q2*Q7 + 4*K2*K4*Q1*Q8 + 4*K2*K4*Q2*Q7 - 4*K1*K5*Q1*Q9 - "
        "4*K1*K5*Q3*Q7 - 4*K2*K4*Q1*Q9 - 4*K2*K4*Q3*Q7 - 4*K2*K5*Q1*Q8 - "
        "4*K2*K5*Q2*Q7 - 12*K2*K5*Q1*Q9 - 12*K2*K5*Q3*Q7 - 8*K1*K2*Q7*Q8 - "
        "16*K3*K4*Q4*Q7 - 8*K4*K5*Q4*Q5 + 8*K1*K2*Q7*Q9 - 16*K3*K5*Q4*Q7 + "
        "8*K4*K5*Q4*Q6 + 12*K3*K4*Q5*Q8 + 4*K3*K4*Q5*Q9 + 4*K3*K4*Q6*Q8 + "
        "4*K3*K5*Q5*Q8 - 4*K3*K4*Q6*Q9 - 4*K3*K5*Q5*Q9 - 4*K3*K5*Q6*Q8 - "
        "12*K3*K5*Q6*Q9 - 16*K3*K4*Q1*Q4*lambda1 - 16*K3*K5*Q1*Q4*lambda1 - "
        "24*K1*K4*Q4*Q5*lambda1 + 12*K3*K4*Q2*Q5*lambda1 - 16*K1*K3*Q4*Q7*lambda1 - "
        "8*K1*K4*Q4*Q6*lambda1 - 8*K1*K5*Q4*Q5*lambda1 - 8*K2*K4*Q4*Q5*lambda1 + "
        "4*K3*K4*Q2*Q6*lambda1 + 4*K3*K4*Q3*Q5*lambda1 + 4*K3*K5*Q2*Q5*lambda1 + "
        "8*K1*K5*Q4*Q6*lambda1 - 16*K2*K3*Q4*Q7*lambda1 + 8*K2*K4*Q4*Q6*lambda1 + "
        "8*K2*K5*Q4*Q5*lambda1 - 4*K3*K4*Q3*Q6*lambda1 - 4*K3*K5*Q2*Q6*lambda1 - "
        "4*K3*K5*Q3*Q5*lambda1 + 12*K1*K3*Q5*Q8*lambda1 + 24*K2*K5*Q4*Q6*lambda1 - "
        "12*K3*K5*Q3*Q6*lambda1 + 4*K1*K3*Q5*Q9*lambda1 + 4*K1*K3*Q6*Q8*lambda1 + "
        "4*K2*K3*Q5*Q8*lambda1 - 4*K1*K3*Q6*Q9*lambda1 - 4*K2*K3*Q5*Q9*lambda1 - "
        "4*K2*K3*Q6*Q8*lambda1 - 12*K2*K3*Q6*Q9*lambda1 + 16*K1*K3*L^2*Q1*Q4 + "
        "16*K2*K3*L^2*Q1*Q4 - 12*K1*K3*L^2*Q2*Q5 + 8*K1*K2*L^2*Q4*Q5 - "
        "4*K1*K3*L^2*Q2*Q6 - 4*K1*K3*L^2*Q3*Q5 - 4*K2*K3*L^2*Q2*Q5 - "
        "8*K1*K2*L^2*Q4*Q6 + 4*K1*K3*L^2*Q3*Q6 + 4*K2*K3*L^2*Q2*Q6 + "
        "4*K2*K3*L^2*Q3*Q5 + 12*K2*K3*L^2*Q3*Q6 - 16*K1*K3*Q1*Q4*lambda1^2 - "
        "16*K2*K3*Q1*Q4*lambda1^2 + 12*K1*K3*Q2*Q5*lambda1^2 - "
        "8*K1*K2*Q4*Q5*lambda1^2 + 4*K1*K3*Q2*Q6*lambda1^2 + 4*K1*K3*Q3*Q5*lambda1^2 "
        "+ 4*K2*K3*Q2*Q5*lambda1^2 + 8*K1*K2*Q4*Q6*lambda1^2 - "
        "4*K1*K3*Q3*Q6*lambda1^2 - 4*K2*K3*Q2*Q6*lambda1^2 - 4*K2*K3*Q3*Q5*lambda1^2 "
        "- 12*K2*K3*Q3*Q6*lambda1^2 "
    ),
    2: (
        "- 4*K1^2*L^2*Q4^2 + 4*K1^2*L^2*Q5^2 + 4*K1^2*L^2*Q5*Q6 + "
        "4*K1^2*Q4^2*lambda1^2 - 4*K1^2*Q5^2*lambda1^2 - 4*K1^2*Q5*Q6*lambda1^2 + "
        "4*K1^2*Q7^2 - 4*K1^2*Q8^2 - 4*K1^2*Q8*Q9 - 8*K1*K2*L^2*Q4^2 + "
        "4*K1*K2*L^2*Q5^2 - 4*K1*K2*L^2*Q6^2 + 8*K1*K2*Q4^2*lambda1^2 - "
        "4*K1*K2*Q5^2*lambda1^2 + 4*K1*K2*Q6^2*lambda1^2 + 8*K1*K2*Q7^2 - "
        "4*K1*K2*Q8^2 + 4*K1*K2*Q9^2 + 8*K1*K3*L^2*Q1*Q5 + 8*K1*K3*L^2*Q1*Q6 + "
        "8*K1*K3*L^2*Q2*Q4 + 8*K1*K3*L^2*Q3*Q4 - 8*K1*K3*Q1*Q5*lambda1^2 - "
        "8*K1*K3*Q1*Q6*lambda1^2 - 8*K1*K3*Q2*Q4*lambda1^2 - 8*K1*K3*Q3*Q4*lambda1^2 "
        "- 8*K1*K3*Q4*Q8*lambda1 - 8*K1*K3*Q4*Q9*lambda1 - 8*K1*K3*Q5*Q7*lambda1 - "
        "8*K1*K3*Q6*Q7*lambda1 - 8*K1*K4*Q1*Q7 + 8*K1*K4*Q2*Q8 + 4*K1*K4*Q2*Q9 + "
        "4*K1*K4*Q3*Q8 + 8*K1*K4*Q4^2*lambda1 - 8*K1*K4*Q5^2*lambda1 - "
        "8*K1*K4*Q5*Q6*lambda1 - 8*K1*K5*Q1*Q7 + 4*K1*K5*Q2*Q8 - 4*K1*K5*Q3*Q9 + "
        "8*K1*K5*Q4^2*lambda1 - 4*K1*K5*Q5^2*lambda1 + 4*K1*K5*Q6^2*lambda1 - "
        "4*K2^2*L^2*Q4^2 - 4*K2^2*L^2*Q5^2*Q6 - 4*K2^2*L^2*Q6^2 + "
        "4*K2^2*Q4^2*lambda1^2 + 4*K2^2*Q5^2*Q6*lambda1^2 + 4*K2^2*Q6^2*lambda1^2 + "
        "4*K2^2*Q7^2 + 4*K2^2*Q8*Q9 + 4*K2^2*Q9^2 + 8*K2*K3*L^2*Q1*Q5 + "
        "8*K2*K3*L^2*Q1*Q6 + 8*K2*K3*L^2*Q2*Q4 + 8*K2*K3*L^2*Q3*Q4 - "
        "8*K2*K3*Q1*Q5*lambda1^2 - 8*K2*K3*Q1*Q6*lambda1^2 - 8*K2*K3*Q2*Q4*lambda1^2 "
        "- 8*K2*K3*Q3*Q4*lambda1^2 - 8*K2*K3*Q4*Q8*lambda1 - 8*K2*K3*Q4*Q9*lambda1 - "
        "8*K2*K3*Q5*Q7*lambda1 - 8*K2*K3*Q6*Q7*lambda1 - 8*K2*K4*Q1*Q7 + "
        "4*K2*K4*Q2*Q8 - 4*K2*K4*Q3*Q9 + 8*K2*K4*Q4^2*lambda1 - 4*K2*K4*Q5^2*lambda1 "
        "+ 4*K2*K4*Q6^2*lambda1 - 8*K2*K5*Q1*Q7 - 4*K2*K5*Q2*Q9 - 4*K2*K5*Q3*Q8 - "
        "8*K2*K5*Q3*Q9 + 8*K2*K5*Q4^2*lambda1 + 8*K2*K5*Q5*Q6*lambda1 + "
        "8*K2*K5*Q6^2*lambda1 - 4*K3^2*L^2*Q2^2 - 8*K3^2*L^2*Q2*Q3 - 4*K3^2*L^2*Q3^2 "
        "+ 4*K3^2*Q2^2*lambda1^2 + 8*K3^2*Q2*Q3*lambda1^2 + 8*K3^2*Q2*Q8*lambda1 + "
        "8*K3^2*Q2*Q9*lambda1 + 4*K3^2*Q3^2*lambda1^2 + 8*K3^2*Q3*Q8*lambda1 + "
        "8*K3^2*Q3*Q9*lambda1 + 4*K3^2*Q8^2 + 8*K3^2*Q8*Q9 + 4*K3^2*Q9^2 - "
        "8*K3*K4*Q1*Q5*lambda1 - 8*K3*K4*Q1*Q6*lambda1 - 8*K3*K4*Q2*Q4*lambda1 - "
        "8*K3*K4*Q3*Q4*lambda1 - 8*K3*K4*Q4*Q8 - 8*K3*K4*Q4*Q9 - 8*K3*K4*Q5*Q7 - "
        "8*K3*K4*Q6*Q7 - 8*K3*K5*Q1*Q5*lambda1 - 8*K3*K5*Q1*Q6*lambda1 - "
        "8*K3*K5*Q2*Q4*lambda1 - 8*K3*K5*Q3*Q4*lambda1 - 8*K3*K5*Q4*Q8 - "
        "8*K3*K5*Q4*Q9 - 8*K3*K5*Q5*Q7 - 8*K3*K5*Q6*Q7 + 4*K4^2*Q1^2 - 4*K4^2*Q2^2 - "
        "4*K4^2*Q2*Q3 + 4*K4^2*Q4^2 - 4*K4^2*Q5^2 - 4*K4^2*Q5*Q6 + 8*K4*K5*Q1^2 - "
        "4*K4*K5*Q2^2 + 4*K4*K5*Q3^2 + 8*K4*K5*Q4^2 - 4*K4*K5*Q5^2 + 4*K4*K5*Q6^2 + "
        "4*K5^2*Q1^2 + 4*K5^2*Q2*Q3 + 4*K5^2*Q3^2 + 4*K5^2*Q4^2 + 4*K5^2*Q5*Q6 + "
        "4*K5^2*Q6^2 "
    ),
    1: (
        "4*K4^2*Q1*Q2 + 4*K4^2*Q1*Q3 + 4*K5^2*Q1*Q2 + 4*K5^2*Q1*Q3 + 4*K4^2*Q4*Q5 + "
        "4*K4^2*Q4*Q6 + 4*K5^2*Q4*Q5 + 4*K5^2*Q4*Q6 + 4*K1^2*Q7*Q8 + 4*K1^2*Q7*Q9 + "
        "4*K2^2*Q7*Q8 + 4*K2^2*Q7*Q9 - 4*K1^2*L^2*Q4*Q5 - 4*K1^2*L^2*Q4*Q6 - "
        "4*K2^2*L^2*Q4*Q5 - 4*K2^2*L^2*Q4*Q6 + 4*K1^2*Q4*Q5*lambda1^2 + "
        "4*K1^2*Q4*Q6*lambda1^2 + 4*K2^2*Q4*Q5*lambda1^2 + 4*K2^2*Q4*Q6*lambda1^2 + "
        "8*K4*K5*Q1*Q2 + 8*K4*K5*Q1*Q3 - 4*K1*K4*Q1*Q8 - 4*K1*K4*Q2*Q7 - "
        "4*K1*K4*Q1*Q9 - 4*K1*K4*Q3*Q7 - 4*K1*K5*Q1*Q8 - 4*K1*K5*Q2*Q7 - "
        "4*K2*K4*Q1*Q8 - 4*K2*K4*Q2*Q7 - 4*K1*K5*Q1*Q9 - 4*K1*K5*Q3*Q7 - "
        "4*K2*K4*Q1*Q9 - 4*K2*K4*Q3*Q7 - 4*K2*K5*Q1*Q8 - 4*K2*K5*Q2*Q7 - "
        "4*K2*K5*Q1*Q9 - 4*K2*K5*Q3*Q7 + 8*K1*K2*Q7*Q8 + 8*K4*K5*Q4*Q5 + "
        "8*K1*K2*Q7*Q9 + 8*K4*K5*Q4*Q6 - 4*K3*K4*Q5*Q8 - 4*K3*K4*Q5*Q9 - "
        "4*K3*K4*Q6*Q8 - 4*K3*K5*Q5*Q8 - 4*K3*K4*Q6*Q9 - 4*K3*K5*Q5*Q9 - "
        "4*K3*K5*Q6*Q8 - 4*K3*K5*Q6*Q9 + 8*K1*K4*Q4*Q5*lambda1 - "
        "4*K3*K4*Q2*Q5*lambda1 + 8*K1*K4*Q4*Q6*lambda1 + 8*K1*K5*Q4*Q5*lambda1 + "
        "8*K2*K4*Q4*Q5*lambda1 - 4*K3*K4*Q2*Q6*lambda1 - 4*K3*K4*Q3*Q5*lambda1 - "
        "4*K3*K5*Q2*Q5*lambda1 + 8*K1*K5*Q4*Q6*lambda1 + 8*K2*K4*Q4*Q6*lambda1 + "
        "8*K2*K5*Q4*Q5*lambda1 - 4*K3*K4*Q3*Q6*lambda1 - 4*K3*K5*Q2*Q6*lambda1 - "
        "4*K3*K5*Q3*Q5*lambda1 - 4*K1*K3*Q5*Q8*lambda1 + 8*K2*K5*Q4*Q6*lambda1 - "
        "4*K3*K5*Q3*Q6*lambda1 - 4*K1*K3*Q5*Q9*lambda1 - 4*K1*K3*Q6*Q8*lambda1 - "
        "4*K2*K3*Q5*Q8*lambda1 - 4*K1*K3*Q6*Q9*lambda1 - 4*K2*K3*Q5*Q9*lambda1 - "
        "4*K2*K3*Q6*Q8*lambda1 - 4*K2*K3*Q6*Q9*lambda1 + 4*K1*K3*L^2*Q2*Q5 - "
        "8*K1*K2*L^2*Q4*Q5 + 4*K1*K3*L^2*Q2*Q6 + 4*K1*K3*L^2*Q3*Q5 + "
        "4*K2*K3*L^2*Q2*Q5 - 8*K1*K2*L^2*Q4*Q6 + 4*K1*K3*L^2*Q3*Q6 + "
        "4*K2*K3*L^2*Q2*Q6 + 4*K2*K3*L^2*Q3*Q5 + 4*K2*K3*L^2*Q3*Q6 - "
        "4*K1*K3*Q2*Q5*lambda1^2 + 8*K1*K2*Q4*Q5*lambda1^2 - 4*K1*K3*Q2*Q6*lambda1^2 "
        "- 4*K1*K3*Q3*Q5*lambda1^2 - 4*K2*K3*Q2*Q5*lambda1^2 + "
        "8*K1*K2*Q4*Q6*lambda1^2 - 4*K1*K3*Q3*Q6*lambda1^2 - 4*K2*K3*Q2*Q6*lambda1^2 "
        "- 4*K2*K3*Q3*Q5*lambda1^2 - 4*K2*K3*Q3*Q6*lambda1^2 "
    ),
    0: (
        "- K1^2*L^2*Q5^2 - 2*K1^2*L^2*Q5*Q6 - K1^2*L^2*Q6^2 + K1^2*Q5^2*lambda1^2 + "
        "2*K1^2*Q5*Q6*lambda1^2 + K1^2*Q6^2*lambda1^2 + K1^2*Q8^2 + 2*K1^2*Q8*Q9 + "
        "K1^2*Q9^2 - 2*K1*K2*L^2*Q5^2 - 4*K1*K2*L^2*Q5*Q6 - 2*K1*K2*L^2*Q6^2 + "
        "2*K1*K2*Q5^2*lambda1^2 + 4*K1*K2*Q5*Q6*lambda1^2 + 2*K1*K2*Q6^2*lambda1^2 + "
        "2*K1*K2*Q8^2 + 4*K1*K2*Q8*Q9 + 2*K1*K2*Q9^2 - 2*K1*K4*Q2*Q8 - 2*K1*K4*Q2*Q9 "
        "- 2*K1*K4*Q3*Q8 - 2*K1*K4*Q3*Q9 + 2*K1*K4*Q5^2*lambda1 + "
        "4*K1*K4*Q5*Q6*lambda1 + 2*K1*K4*Q6^2*lambda1 - 2*K1*K5*Q2*Q8 - 2*K1*K5*Q2*Q9 "
        "- 2*K1*K5*Q3*Q8 - 2*K1*K5*Q3*Q9 + 2*K1*K5*Q5^2*lambda1 + "
        "4*K1*K5*Q5*Q6*lambda1 + 2*K1*K5*Q6^2*lambda1 - K2^2*L^2*Q5^2 - "
        "2*K2^2*L^2*Q5*Q6 - K2^2*L^2*Q6^2 + K2^2*Q5^2*lambda1^2 + "
        "2*K2^2*Q5*Q6*lambda1^2 + K2^2*Q6^2*lambda1^2 + K2^2*Q8^2 + 2*K2^2*Q8*Q9 + "
        "K2^2*Q9^2 - 2*K2*K4*Q2*Q8 - 2*K2*K4*Q2*Q9 - 2*K2*K4*Q3*Q8 - 2*K2*K4*Q3*Q9 + "
        "2*K2*K4*Q5^2*lambda1 + 4*K2*K4*Q5*Q6*lambda1 + 2*K2*K4*Q6^2*lambda1 - "
        "2*K2*K5*Q2*Q8 - 2*K2*K5*Q2*Q9 - 2*K2*K5*Q3*Q8 - 2*K2*K5*Q3*Q9 + "
        "2*K2*K5*Q5^2*lambda1 + 4*K2*K5*Q5*Q6*lambda1 + 2*K2*K5*Q6^2*lambda1 + "
        "K4^2*Q2^2 + 2*K4^2*Q2*Q3 + K4^2*Q3^2 + K4^2*Q5^2 + 2*K4^2*Q5*Q6 + K4^2*Q6^2 "
        "+ 2*K4*K5*Q2^2 + 4*K4*K5*Q2*Q3 + 2*K4*K5*Q3^2 + 2*K4*K5*Q5^2 + 4*K4*K5*Q5*Q6 "
        "+ 2*K4*K5*Q6^2 + K5^2*Q2^2 + 2*K5^2*Q2*Q3 + K5^2*Q3^2 + K5^2*Q5^2 + "
        "2*K5^2*Q5*Q6 + K5^2*Q6^2 "
    ),
}
_TERM = re.compile(r"^(?:(\d+)\*)?([A-Za-z]\w*(?:\^\d+)?(?:\*[A-Za-z]\w*(?:\^\d+)?)*)$")


def parse_terms(text: str) -> list[tuple[int, dict[str, int]]]:
    """The terms of a sum of monomials written ``- 2*K1^2*Q5 + Q6^2 ...``.

    Returns
    -------
    list of (int, dict of str to int)
        Each term's signed integer coefficient and its powers, ``{symbol: power}``.

    Raises
    ------
    ValueError
        If a term is not an integer times a product of symbols with integer powers.

    Examples
    --------
    >>> parse_terms("- K1^2*L^2*Q5^2 + 2*K1*K2*Q6")
    [(-1, {'K1': 2, 'L': 2, 'Q5': 2}), (2, {'K1': 1, 'K2': 1, 'Q6': 1})]
    """
    if not isinstance(text, str):
        raise ValueError(f"text must be a str, got {text!r:.80}")
    terms = []
    for sign, body in re.findall(r"([+-]?)\s*([^+-]+)", text):
        match = _TERM.match(body.strip())
        if match is None:
            raise ValueError(f"not a monomial: {body.strip()!r}")
        coefficient = int(match.group(1) or 1) * (-1 if sign == "-" else 1)
        powers = {}
        for factor in match.group(2).split("*"):
            name, _, power = factor.partition("^")
            powers[name] = powers.get(name, 0) + int(power or 1)
        terms.append((coefficient, powers))
    return terms


def annex_i_terms() -> dict[int, list[tuple[int, dict[str, int]]]]:
    """Annex I's printed coefficients, parsed: ``{k: [(coefficient, {symbol: power}), ...]}``.

    Examples
    --------
    >>> terms = annex_i_terms()
    >>> len(terms[8]), terms[8][0]
    (73, (-1, {'K1': 2, 'L': 2, 'Q5': 2}))
    """
    return {k: parse_terms(text) for k, text in ANNEX_I.items()}
