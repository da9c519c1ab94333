"""distance_matrix on a Dask cluster (an in-process local cluster: cheap)."""

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.errors import InvalidInputError

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_dask_client_and_address_give_the_local_result(client, kimia_signatures):
    sigs = kimia_signatures[::9]
    local = mx.distance_matrix(sigs, n_jobs=1)
    assert np.array_equal(mx.distance_matrix(sigs, scheduler=client), local)
    assert np.array_equal(mx.distance_matrix(sigs, scheduler=client.scheduler.address), local)


def test_bad_scheduler_name():
    with pytest.raises(InvalidInputError, match="scheduler"):
        mx.distance_matrix([np.eye(20, dtype=bool)] * 2, scheduler="processes")
