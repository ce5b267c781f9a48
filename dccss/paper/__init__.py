"""What is specific to Bianco, Monti & Belfiore (2021): Table 1's devices (``prototypes``), the
figure kinds that draw Figs. 7-12 and 17-20 (``figures``) and the check of every number the paper
states (``validation``). What each figure shows and which numbers are checked is data, in the
workflow's ``config/``.
"""
