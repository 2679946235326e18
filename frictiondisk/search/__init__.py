"""Where the jump is: bisection and its root finders, prescan, certification, basin
sampling. State machines that know nothing of Dask or files."""
